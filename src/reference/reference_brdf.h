// BRDFs of the reference renderer: evaluation, sampling and pdf in double precision, in a local
// shading frame (n = +z, tangent = +x). This is the ground truth the shading techniques are measured
// against, written for clarity, not speed; the shared shading code has its own (float, exact-math)
// implementations, tested against these.
//
// Every lobe is f = kd / pi + ks * fs(wi, wo), with wo the direction to the viewer, wi to the light,
// both unit vectors in the local frame, and the integrand f * cos(theta_i) over the upper hemisphere.
//   phong      fs = (e + 2) / (2 pi) cos^e(alpha), alpha = angle(wi, reflect(wo))          (normalized Phong,
//              Lafortune & Willems 1994); sampled about the mirror direction: cos alpha = u^(1/(e+1)),
//              pdf = (e + 1) / (2 pi) cos^e(alpha).
//   blinn      fs = (e + 8) / (8 pi) cos^e(theta_h)                                         (normalized Blinn-Phong);
//              h sampled with pdf_h = (e + 1) / (2 pi) cos^e(theta_h), pdf = pdf_h / (4 wo.h).
//   ggx        fs = D G / (4 cos_i cos_o), D = a^2 / (pi cos^4(theta_h) (a^2 + tan^2(theta_h))^2),
//              G = G1(wi) G1(wo), G1(v) = 2 / (1 + sqrt(1 + a^2 tan^2(theta_v)))            (Walter et al. 2007);
//              h sampled with pdf_h = D cos(theta_h): tan^2(theta_h) = a^2 u / (1 - u); pdf = pdf_h / (4 wo.h).
//   ward       fs = exp(-tan^2(theta_h) (cos^2 phi_h / ax^2 + sin^2 phi_h / ay^2)) /
//                   (4 pi ax ay sqrt(cos_i cos_o))                                          (Ward 1992, as in
//              Walter 2005 "Notes on the Ward BRDF"); h sampled with
//              pdf_h = exp(-tan^2(theta_h)(...)) / (pi ax ay cos^3(theta_h)), pdf = pdf_h / (4 wo.h).
//   lafortune  fs = sum_k rho_k max(s_k . wi, 0)^n_k, s_k = (Cx wo.x, Cy wo.y, Cz wo.z)       (Lafortune et al. 1997,
//              one or two lobes); lobe k is a Phong lobe of exponent n_k about a_k = s_k / |s_k| with
//              integral m_k = rho_k |s_k|^n_k 2 pi / (n_k + 1); picked with P_k = m_k / sum m, then sampled as
//              Phong about a_k: pdf = sum_k P_k (n_k + 1) / (2 pi) max(a_k . wi, 0)^n_k.
//   mirror     fs = delta(wi - reflect(wo)): handled by the renderer, not sampled here.
// Sampling picks the diffuse lobe (cosine-weighted) with probability lum(kd) / (lum(kd) + lum(ks)),
// else the glossy lobe; pdf() is that mixture.
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace shadetwin::reference {

struct D3 {
  double x = 0, y = 0, z = 0;
};
inline D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline D3 normalize(D3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }

enum class Lobe { Phong, Blinn, Ggx, Ward, Lafortune, Mirror };

struct RefLafortuneLobe {
  double c[3] = {-1, -1, 1};
  double n = 1, rho = 0;  // rho = 0: absent
};

struct RefBrdf {
  Lobe lobe = Lobe::Phong;
  double kd[3] = {0.5, 0.5, 0.5}, ks[3] = {0.04, 0.04, 0.04};
  double exponent = 100, ax = 0.2, ay = 0.2;
  RefLafortuneLobe lobes[2];

  /// Lafortune: s_k, its length and the lobe's share P_k of the sampling (P_1 = 1 - P_0).
  D3 lafortuneS(int k, D3 wo) const { return {lobes[k].c[0] * wo.x, lobes[k].c[1] * wo.y, lobes[k].c[2] * wo.z}; }
  double lafortuneP0(D3 wo) const {
    double m[2];
    for (int k = 0; k < 2; ++k) {
      const double l = std::sqrt(dot(lafortuneS(k, wo), lafortuneS(k, wo)));
      m[k] = l > 0 ? lobes[k].rho * std::pow(l, lobes[k].n) / (lobes[k].n + 1) : 0.0;
    }
    return m[0] + m[1] > 0 ? m[0] / (m[0] + m[1]) : 1.0;
  }

  double diffuseWeight() const {
    const double d = 0.2126 * kd[0] + 0.7152 * kd[1] + 0.0722 * kd[2];
    const double s = 0.2126 * ks[0] + 0.7152 * ks[1] + 0.0722 * ks[2];
    if (lobe == Lobe::Mirror) return 1.0;  // the delta lobe is not sampled here
    return d + s > 0 ? d / (d + s) : 1.0;
  }

  /// fs(wi, wo) of the glossy lobe (without ks); 0 below either horizon.
  double glossy(D3 wi, D3 wo) const {
    if (wi.z <= 0 || wo.z <= 0) return 0;
    constexpr double pi = std::numbers::pi;
    switch (lobe) {
      case Lobe::Phong: {
        const D3 r{-wo.x, -wo.y, wo.z};
        const double c = std::max(0.0, dot(wi, r));
        return (exponent + 2) / (2 * pi) * std::pow(c, exponent);
      }
      case Lobe::Blinn: {
        const D3 h = normalize(wi + wo);
        return (exponent + 8) / (8 * pi) * std::pow(std::max(0.0, h.z), exponent);
      }
      case Lobe::Ggx: {
        const D3 h = normalize(wi + wo);
        return ggxD(h) * ggxG1(wi) * ggxG1(wo) / (4 * wi.z * wo.z);
      }
      case Lobe::Ward: {
        const D3 h = normalize(wi + wo);
        return std::exp(-wardExponent(h)) / (4 * pi * ax * ay * std::sqrt(wi.z * wo.z));
      }
      case Lobe::Lafortune: {
        double f = 0;
        for (int k = 0; k < 2; ++k) f += lobes[k].rho * std::pow(std::max(0.0, dot(lafortuneS(k, wo), wi)), lobes[k].n);
        return f;
      }
      case Lobe::Mirror: return 0;
    }
    return 0;
  }

  /// Glossy lobe's own pdf of wi (solid angle).
  double glossyPdf(D3 wi, D3 wo) const {
    if (wi.z <= 0 || wo.z <= 0) return 0;
    constexpr double pi = std::numbers::pi;
    switch (lobe) {
      case Lobe::Phong: {
        const D3 r{-wo.x, -wo.y, wo.z};
        const double c = std::max(0.0, dot(wi, r));
        return (exponent + 1) / (2 * pi) * std::pow(c, exponent);
      }
      case Lobe::Blinn: {
        const D3 h = normalize(wi + wo);
        return (exponent + 1) / (2 * pi) * std::pow(std::max(0.0, h.z), exponent) / (4 * dot(wo, h));
      }
      case Lobe::Ggx: {
        const D3 h = normalize(wi + wo);
        return ggxD(h) * h.z / (4 * dot(wo, h));
      }
      case Lobe::Ward: {
        const D3 h = normalize(wi + wo);
        return std::exp(-wardExponent(h)) / (pi * ax * ay * h.z * h.z * h.z) / (4 * dot(wo, h));
      }
      case Lobe::Lafortune: {
        const double p0 = lafortuneP0(wo);
        double p = 0;
        for (int k = 0; k < 2; ++k) {
          const D3 s = lafortuneS(k, wo);
          if (dot(s, s) <= 0) continue;
          const double c = std::max(0.0, dot(normalize(s), wi));
          p += (k == 0 ? p0 : 1 - p0) * (lobes[k].n + 1) / (2 * pi) * std::pow(c, lobes[k].n);
        }
        return p;
      }
      case Lobe::Mirror: return 0;
    }
    return 0;
  }

  /// Mixture pdf of sample().
  double pdf(D3 wi, D3 wo) const {
    const double wd = diffuseWeight();
    const double cosPdf = wi.z > 0 ? wi.z / std::numbers::pi : 0.0;
    return wd * cosPdf + (1 - wd) * glossyPdf(wi, wo);
  }

  /// Samples wi from the mixture with uniforms (u0, u1, u2); u0 picks the lobe. May return a
  /// direction below the horizon (its f and pdf are then 0: the sample is lost, which is unbiased).
  D3 sample(D3 wo, double u0, double u1, double u2) const {
    constexpr double pi = std::numbers::pi;
    if (u0 < diffuseWeight()) {
      const double r = std::sqrt(u1), phi = 2 * pi * u2;
      return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1))};
    }
    switch (lobe) {
      case Lobe::Phong: {
        const double c = std::pow(u1, 1 / (exponent + 1)), s = std::sqrt(std::max(0.0, 1 - c * c)), phi = 2 * pi * u2;
        const D3 r{-wo.x, -wo.y, wo.z};
        D3 t, b;
        frame(r, t, b);
        return t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + r * c;
      }
      case Lobe::Blinn: {
        const double c = std::pow(u1, 1 / (exponent + 1)), s = std::sqrt(std::max(0.0, 1 - c * c)), phi = 2 * pi * u2;
        return reflect(wo, {s * std::cos(phi), s * std::sin(phi), c});
      }
      case Lobe::Ggx: {
        const double a2 = ax * ax, t2 = a2 * u1 / std::max(1e-300, 1 - u1), c = 1 / std::sqrt(1 + t2);
        const double s = std::sqrt(std::max(0.0, 1 - c * c)), phi = 2 * pi * u2;
        return reflect(wo, {s * std::cos(phi), s * std::sin(phi), c});
      }
      case Lobe::Ward: {
        // phi_h = atan(ay / ax * tan(2 pi u2)), kept in the quadrant of 2 pi u2 (Walter 2005).
        double phi = std::atan(ay / ax * std::tan(2 * pi * u2));
        if (u2 > 0.25 && u2 <= 0.75) phi += pi;
        else if (u2 > 0.75) phi += 2 * pi;
        const double cp = std::cos(phi), sp = std::sin(phi);
        const double t2 = -std::log(std::max(1e-300, u1)) / (cp * cp / (ax * ax) + sp * sp / (ay * ay));
        const double c = 1 / std::sqrt(1 + t2), s = std::sqrt(std::max(0.0, 1 - c * c));
        return reflect(wo, {s * cp, s * sp, c});
      }
      case Lobe::Lafortune: {
        const double p0 = lafortuneP0(wo);
        const int k = u1 < p0 ? 0 : 1;
        const double uu = k == 0 ? u1 / p0 : (u1 - p0) / (1 - p0);
        const double e = lobes[k].n;
        const double c = std::pow(uu, 1 / (e + 1)), s = std::sqrt(std::max(0.0, 1 - c * c)), phi = 2 * pi * u2;
        const D3 a = normalize(lafortuneS(k, wo));
        D3 t, b;
        frame(a, t, b);
        return t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + a * c;
      }
      case Lobe::Mirror: break;
    }
    return {0, 0, -1};
  }

  double ggxD(D3 h) const {
    if (h.z <= 0) return 0;
    const double c2 = h.z * h.z, t2 = (1 - c2) / c2, a2 = ax * ax;
    return a2 / (std::numbers::pi * c2 * c2 * (a2 + t2) * (a2 + t2));
  }
  double ggxG1(D3 v) const {
    const double c2 = v.z * v.z, t2 = (1 - c2) / c2;
    return 2 / (1 + std::sqrt(1 + ax * ax * t2));
  }
  double wardExponent(D3 h) const {
    const double c2 = h.z * h.z;
    if (c2 <= 0) return 1e300;
    const double s2 = h.x * h.x + h.y * h.y;
    if (s2 <= 0) return 0;
    // tan^2 * (cos^2 phi / ax^2 + sin^2 phi / ay^2) = (hx^2 / ax^2 + hy^2 / ay^2) / hz^2
    return (h.x * h.x / (ax * ax) + h.y * h.y / (ay * ay)) / c2;
  }
  static D3 reflect(D3 wo, D3 h) { return h * (2 * dot(wo, h)) - wo; }
  static void frame(D3 n, D3& t, D3& b) {
    const D3 a = std::fabs(n.x) > 0.9 ? D3{0, 1, 0} : D3{1, 0, 0};
    t = normalize(cross(a, n));
    b = cross(n, t);
  }
};

}  // namespace shadetwin::reference
