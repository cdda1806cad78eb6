// The simple deferred shading pass used until filtered importance sampling lands: a perfect mirror
// lookup plus a crude diffuse term (the environment's MIP level envMaxLod - 1 along the normal),
// both through trilinear textureLod of the equirectangular environment. Background pixels (G0.w = 0)
// show the environment along the camera ray.

const float kInvPi = 0.318309886f;
const float kInv2Pi = 0.159154943f;

// Equirectangular lookup: u from the azimuth about +y (u = 1/2 looks down -z), v = polar angle / pi.
Float2 equirectUv(Float3 d) {
  PRECISE Float u = exAtan2(d.x, -d.z) * kInv2Pi + 0.5f;
  PRECISE Float v = exAcos(clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  return Float2(u, v);
}

// Camera ray through the centre of pixel (px, py): fwd + right * ndcX + down * ndcY, normalised.
// right / down are pre-scaled by tan(fov / 2) (and the aspect ratio) on the host.
Float3 cameraRay(Float3 fwd, Float3 right, Float3 down, Float px, Float py, Float invW, Float invH) {
  PRECISE Float nx = (px + 0.5f) * invW * 2.0f - 1.0f;
  PRECISE Float ny = (py + 0.5f) * invH * 2.0f - 1.0f;
  PRECISE Float3 d = fwd + right * nx;
  d = d + down * ny;
  return exNormalize(d);
}

Float4 shadeMirror(Sampler2D env, Float envMaxLod, Float intensity, Float4 g0, Float4 g1, Float3 eye, Float3 ray,
                   Float3 diffuse, Float3 specular) {
  Mask geometry = g0.w != 0.0f;
  Float3 p = Float3(g0.x, g0.y, g0.z);
  Float3 n = exNormalize(Float3(g1.x, g1.y, g1.z));
  Float3 v = exNormalize(eye - p);
  PRECISE Float ndv = dot(n, v);
  PRECISE Float3 r = n * (2.0f * ndv) - v;
  r = select(geometry, r, ray);
  Float4 mirror = textureLod(env, equirectUv(r), 0.0f);
  Float4 irr = textureLod(env, equirectUv(n), max(envMaxLod - 1.0f, 0.0f));
  PRECISE Float3 c = Float3(mirror.x, mirror.y, mirror.z) * specular + Float3(irr.x, irr.y, irr.z) * diffuse;
  c = select(geometry, c, Float3(mirror.x, mirror.y, mirror.z));
  c = c * intensity;
  return Float4(c.x, c.y, c.z, 1.0f);
}
