// The exact sphere (src/core/model/shapes/sphere.hpp): its MDR image against
// the transform of f(r) = R - sqrt(R^2 - r^2) by Gauss-Kronrod, its elastic
// force against Hertz's for the full sphere, the refusal of a contact that
// would reach R, and the paraboloid limit: its stationary states approach the
// parabola's of the same R, the difference falling as (a/R)^2. (Its image's
// derivatives and integrals: tests/test_shapes.cpp; its stationary states
// against the branch ODEs: tests/test_profiles.cpp; its transients: the
// profile case set.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "core/metrics/stationary.hpp"
#include "core/model/case.hpp"
#include "core/solvers/checked_case.hpp"

namespace mdrmap {
namespace {

double rel(double a, double b) {
  return a == b ? 0.0 : std::fabs(a - b) / std::fmax(std::fabs(a), std::fabs(b));
}

// g(x) = |x| int_0^|x| f'(r) / sqrt(x^2 - r^2) dr, in r = |x| sin t:
// |x| int_0^(pi/2) f'(|x| sin t) dt, f'(r) = r / sqrt(R^2 - r^2).
TEST(Sphere, ImageIsTheMdrTransformOfTheSphere) {
  const double R = 2.0, half_pi = boost::math::constants::half_pi<double>();
  const Sphere s{R};
  for (const double u : {1e-3, 0.1, 0.5, 0.9, 0.99}) {
    const double x = u * R;
    auto fp = [&](double t) {
      const double r = x * std::sin(t);
      return r / std::sqrt((R - r) * (R + r));
    };
    const double g = x * boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
                             fp, 0.0, half_pi, 12, 1e-15);
    EXPECT_LT(rel(s.g(x), g), 1e-14) << "u = " << u;
    EXPECT_EQ(s.g(-x), s.g(x));
  }
  // the paraboloid at the tip: g / (x^2 / R) - 1 = u^2/3 + u^4/5 + ...
  for (const double u : {1e-3, 1e-2, 1e-1}) {
    const double x = u * R;
    EXPECT_NEAR(s.g(x) / (x * x / R) - 1.0, u * u / 3.0, 0.21 * u * u * u * u) << "u = " << u;
  }
}

// F = (E*/2) [(a^2 + R^2) ln((R + a)/(R - a)) - 2 a R] with E* = 4 G (the
// parabola's 16/3 G a^3 / R is Hertz's 4/3 E* a^3 / R), and its Hertz radius
// inverts it. (Hertz's form loses (R/a)^2 of its digits: the tolerance.)
TEST(Sphere, ElasticForceIsHertzsForTheSphere) {
  const double R = 1.5, G = 0.7, E = 4.0 * G;
  const Sphere s{R};
  for (const double u : {0.05, 0.3, 0.49, 0.51, 0.8, 0.99}) {
    const double a = u * R;
    const double hertz = 0.5 * E * ((a * a + R * R) * std::log((R + a) / (R - a)) - 2.0 * a * R);
    EXPECT_LT(rel(s.elastic_force(a, G), hertz), 1e-14 / (u * u)) << "u = " << u;
    EXPECT_LT(rel(s.hertz_radius(hertz, G), a), 1e-14 / (u * u)) << "u = " << u;
    // d ln F / d ln d = 8 G a d / F (dF/dd = 8 G a), by central differences in d
    const double d = s.g(a), h = 1e-5 * d;
    const double fd = (std::log(s.elastic_force(s.contact_radius(d + h), G)) -
                       std::log(s.elastic_force(s.contact_radius(d - h), G))) /
                      (std::log(d + h) - std::log(d - h));
    EXPECT_NEAR(s.force_exponent(d), fd, 1e-8 * fd) << "u = " << u;
  }
  // the parabola's force at small a/R: F / F_parabola - 1 = (2/5) u^2 + ...
  for (const double u : {1e-3, 1e-2}) {
    const double a = u * R, parabola = 16.0 / 3.0 * G * a * a * a / R;
    EXPECT_NEAR(s.elastic_force(a, G) / parabola - 1.0, 0.4 * u * u, u * u * u * u) << u;
  }
}

Case sphere_case(double R, double d, double tau, double v) {
  Case c = step_case(d, 1.0, tau, v, v);
  c.indenter = Sphere{R};
  return c;
}

// g is infinite at R: a depth or load whose contact radius rounds to R is
// refused, naming the option; one just below is taken.
TEST(Sphere, AContactThatWouldReachRIsRefused) {
  for (const bool load : {false, true}) {
    Case c = sphere_case(1.0, 100.0, 1.0, 1.0);
    if (load) {
      c.loading.d = 0.0;
      c.loading.F0 = 1e30;
    }
    try {
      validate(c);
      ADD_FAILURE() << "a contact radius of R taken";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.option(), load ? "F0" : "d");
      EXPECT_NE(std::string(e.what()).find("not below"), std::string::npos) << e.what();
    }
    if (load)
      c.loading.F0 = 10.0;
    else
      c.loading.d = 5.0;
    EXPECT_NO_THROW(validate(c));
    EXPECT_LT(c.edge_scale(), 1.0);
  }
}

// At a/R -> 0 the sphere is the parabola of its R: at the same depth (or
// load) and the same v tau / a, the stationary states differ by O((a/R)^2):
// the observed order in a/R between a/R = 0.04 and 0.02 is 2.
TEST(Sphere, StationaryStatesTendToTheParabolasAsAOverRFalls) {
  const double R = 1.0;
  for (const bool spectrum : {false, true})
    for (const bool load : {false, true}) {
      double e[2] = {0.0, 0.0};
      const double u[2] = {0.04, 0.02};
      for (int i = 0; i < 2; ++i) {
        const double a = u[i] * R, v = 0.7 * a;
        Case p = step_case(a * a / R, R, spectrum ? 0.0 : 1.0, v, v);
        if (spectrum) p.rheology.branches = {{2.0, 0.3}, {0.5, 5.0}};
        if (load) {
          p.loading.F0 = p.indenter.elastic_force(a, p.rheology.G);
          p.loading.d = 0.0;
        }
        Case s = p;
        s.indenter = Sphere{R};
        const State ps = stationary_state(p, v), ss = stationary_state(s, v);
        e[i] = std::fmax(std::fmax(rel(ss.FN, ps.FN), rel(ss.Fx, ps.Fx)),
                         std::fmax(rel(ss.a2, ps.a2), rel(ss.d, ps.d)));
      }
      const double order = std::log(e[0] / e[1]) / std::log(u[0] / u[1]);
      std::printf("sphere vs parabola (%s, %s): %.3g at a/R = 0.04, %.3g at 0.02: order %.3f\n",
                  spectrum ? "spectrum" : "Kelvin", load ? "load" : "depth", e[0], e[1], order);
      EXPECT_NEAR(order, 2.0, 0.05);
      EXPECT_LT(e[1], u[1] * u[1]);
    }
}

} // namespace
} // namespace mdrmap
