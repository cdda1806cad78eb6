// The bins of the NDF histogram (Gamboa, Guertin, Nowrouzezahrai 2018, "Scalable Appearance
// Filtering for Complex Lighting Effects", §4.1 and §6.1): a micro-normal n (tangent space, z the
// macro normal) falls in ring t = floor(theta * T / thetaMax) (clamped to T - 1; theta = acos n.z)
// and sector p = floor(phi * P / (2 pi)) (phi = atan2(n.y, n.x) in [0, 2 pi)); its bin is t P + p.
// theta and phi come from the exact-math layer, so every build bins every normal alike (the SAT
// built from the bins is then the same integer table on every build). Dialect only.

struct NdfBinning {
  uint rings;        // T: theta bins
  uint sectors;      // P: phi bins
  float ringScale;   // T / thetaMax
  float sectorScale; // P / (2 pi)
};

Uint ndfBin(NdfBinning b, Float3 n) {
  PRECISE Float theta = exAcos(clamp(n.z, -1.0f, 1.0f));
  PRECISE Float phi = exAtan2(n.y, n.x);
  PRECISE Float phi2 = select(phi < 0.0f, phi + 6.28318548f, phi);
  Int t = clamp(Int(floor(theta * b.ringScale)), Int(0), Int(int(b.rings) - 1));
  Int p = clamp(Int(floor(phi2 * b.sectorScale)), Int(0), Int(int(b.sectors) - 1));
  return Uint(t) * b.sectors + Uint(p);
}
