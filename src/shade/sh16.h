// Real spherical harmonics of order 4 (bands l <= 3, 16 functions) for SH visibility (issue 16):
// Sloan, "Stupid Spherical Harmonics (SH) Tricks" (GDC 2008), appendix, with up = y as in
// shade/sh_irradiance.h, whose bands 0-2 are the same functions in the same order:
//   band 0: 0.282095; band 1: 0.488603 (y, z, x);
//   band 2: 1.092548 xy, 1.092548 yz, 0.315392 (3 z^2 - 1), 1.092548 xz, 0.546274 (x^2 - y^2);
//   band 3: 0.590044 y (3 x^2 - y^2), 2.890611 xyz, 0.457046 y (5 z^2 - 1), 0.373176 z (5 z^2 - 3),
//           0.457046 x (5 z^2 - 1), 1.445306 z (x^2 - y^2), 0.590044 x (x^2 - 3 y^2)
// (normalisations sqrt(35/32pi), sqrt(105/4pi), sqrt(21/32pi), sqrt(7/16pi), sqrt(105/16pi); the
// band-3 forms use x^2 + y^2 + z^2 = 1). Orthonormal on the unit sphere: tests/visibility_test.cpp.

// 16 SH coefficients (or basis values), i = 0..15 as (a.x, a.y, a.z, a.w, b.x, ..., d.w): band 0, 1 (3),
// 2 (5), 3 (7), m ascending within a band.
struct Sh16 {
  Float4 a;
  Float4 b;
  Float4 c;
  Float4 d;
};

Sh16 sh16Basis(Float3 v) {
  PRECISE Float xx = v.x * v.x;
  PRECISE Float yy = v.y * v.y;
  PRECISE Float zz = v.z * v.z;
  PRECISE Float b20 = 0.315391565f * (3.0f * zz - 1.0f);
  PRECISE Float b22 = 0.546274215f * (xx - yy);
  PRECISE Float b3m3 = 0.590043604f * (v.y * (3.0f * xx - yy));
  PRECISE Float b3m2 = 2.89061141f * ((v.x * v.y) * v.z);
  PRECISE Float b3m1 = 0.457045794f * (v.y * (5.0f * zz - 1.0f));
  PRECISE Float b30 = 0.373176336f * (v.z * (5.0f * zz - 3.0f));
  PRECISE Float b31 = 0.457045794f * (v.x * (5.0f * zz - 1.0f));
  PRECISE Float b32 = 1.44530571f * (v.z * (xx - yy));
  PRECISE Float b33 = 0.590043604f * (v.x * (xx - 3.0f * yy));
  return Sh16(Float4(Float(0.282094792f), 0.488602512f * v.y, 0.488602512f * v.z, 0.488602512f * v.x),
              Float4(1.09254843f * (v.x * v.y), 1.09254843f * (v.y * v.z), b20, 1.09254843f * (v.x * v.z)),
              Float4(b22, b3m3, b3m2, b3m1), Float4(b30, b31, b32, b33));
}

// sum_i c_i y_i, in i order.
Float sh16Dot(Sh16 c, Sh16 y) {
  PRECISE Float r = dot(c.a, y.a);
  r = r + dot(c.b, y.b);
  r = r + dot(c.c, y.c);
  r = r + dot(c.d, y.d);
  return r;
}

// acc + w v, coefficient by coefficient.
Sh16 sh16AddScaled(Sh16 acc, Sh16 w, Float v) {
  return Sh16(acc.a + w.a * v, acc.b + w.b * v, acc.c + w.c * v, acc.d + w.d * v);
}

