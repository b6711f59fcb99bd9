// The indenter shapes (src/core/model/shapes/, the table Shapes of
// src/core/model/profile.hpp): each shape's image checked against its own g
// by differences and quadrature, for every shape of the table (a shape
// without an example below fails ShapesTable.EveryShapeHasAnExample).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "core/model/params.hpp"
#include "core/model/profile.hpp"

namespace mdrmap {
namespace {

std::vector<Indenter> examples() {
  // (the spheres' contacts at d = 0.01: a/R = 0.1, on the sums, and 0.64,
  // on the closed forms)
  return {Parabola{1.3},   Cone{10.0},      Cone{45.0},      Power{1.5, 0.7}, Power{3.0, 2.0},
          Power{1.0, 1.0}, Power{2.0, 0.5}, Power{1.2, 3.0}, Sphere{1.0},     Sphere{0.02}};
}

std::string label(const Indenter& ind) {
  std::string s = profile_name(ind.profile);
  for (const ParamSpec& p : case_parameters()) {
    Case c;
    c.indenter = ind;
    if (p.profile && p.applies_to(ind.profile))
      s += " " + std::string(p.name) + "=" + format_number(p.get(c));
  }
  return s;
}

// Gauss-Kronrod on either side of the tip, in s = |x|^(1/5) on a piece
// that ends there (g'^2 ~ |x|^(2n-2) is not smooth at the tip).
template <class F> double integral(F f, double l, double r) {
  using boost::math::quadrature::gauss_kronrod;
  auto gk = [](auto h, double a, double b) {
    return gauss_kronrod<double, 61>::integrate(h, a, b, 8, 1e-13);
  };
  auto from_tip = [&](double e) { // int_0^e f, e != 0
    const double sign = e < 0.0 ? -1.0 : 1.0;
    auto h = [&](double t) { return 5.0 * t * t * t * t * f(sign * t * t * t * t * t); };
    return sign * gk(h, 0.0, std::pow(std::fabs(e), 0.2));
  };
  if (l < 0.0 && r > 0.0) return from_tip(r) - from_tip(l);
  return gk(f, l, r);
}

/// f(indenter, its image) for every example, traced by its label.
template <class F> void for_each_example(F f) {
  for (const Indenter& ind : examples()) {
    SCOPED_TRACE(label(ind));
    std::visit([&](const auto& img) { f(ind, img); }, ind.image());
  }
}

struct Path {
  double d, r, k;
  double at(double t) const { return d + (r + k * t) * t; }
};
struct Forcing {
  double h0, h1, h2;
  double at(double t) const { return h0 + (h1 + h2 * t) * t; }
};

TEST(ShapesTable, EveryShapeHasAnExample) {
  for (const Profile p : all_profiles()) {
    bool found = false;
    for (const Indenter& ind : examples())
      found = found || ind.profile == p;
    EXPECT_TRUE(found) << profile_name(p) << " has no example in test_shapes.cpp";
  }
}

// Each shape's parameters are table entries of that shape, and only of it.
TEST(ShapesTable, ParametersAreTheShapes) {
  for (const Indenter& ind : examples()) {
    Case c;
    c.indenter = ind;
    int own = 0;
    for (const ParamSpec& p : case_parameters()) {
      if (!p.profile) continue;
      EXPECT_EQ(p.part, Part::Indenter) << p.name;
      if (!p.applies_to(ind.profile)) {
        EXPECT_EQ(p.get(c), 0.0) << p.name << " of " << label(ind);
        continue;
      }
      ++own;
      EXPECT_TRUE(p.contains(p.get(c))) << label(ind);
    }
    EXPECT_GT(own, 0) << label(ind);
  }
}

// g' and g'' are the derivatives of g; the one-sided slope at the tip is the
// limit of g' there (the cone's kink, 0 where g' is continuous).
TEST(ShapesImage, SlopeAndCurvatureAreTheDerivativesOfG) {
  for_each_example([&]([[maybe_unused]] const Indenter& ind, const auto& img) {
    const double a = img.contact_radius(0.01), h = 1e-6 * a;
    for (const double x : {-0.71 * a, -0.37 * a, 0.37 * a, 0.93 * a}) {
      const double fd = (img.g(x + h) - img.g(x - h)) / (2.0 * h);
      EXPECT_NEAR(img.slope(x), fd, 1e-7 * std::fabs(img.slope(a)));
      EXPECT_EQ(img.side_slope(x, 1), img.slope(x));
      const double fd2 = (img.slope(x + h) - img.slope(x - h)) / (2.0 * h);
      EXPECT_NEAR(img.curvature(x), fd2, 1e-5 * std::fabs(img.slope(a)) / a);
      EXPECT_DOUBLE_EQ(img.lift(x, 3.0), 3.0 * img.slope(x));
      EXPECT_DOUBLE_EQ(img.depth(x, 0.02), 0.02 - img.g(x));
    }
    // (|g'| falls as |x|^(n-1): by 1e-3 of g'(a) at 1e-15 a for n = 1.2)
    const double tiny = 1e-15 * a;
    EXPECT_NEAR(img.slope(tiny), img.apex_slope(), 2e-3 * img.slope(a));
    EXPECT_NEAR(img.slope(-tiny), -img.apex_slope(), 2e-3 * img.slope(a));
    EXPECT_EQ(img.side_slope(0.0, 1), img.apex_slope());
    EXPECT_EQ(img.side_slope(0.0, -1), -img.apex_slope());
    if (img.smooth_apex()) {
      EXPECT_EQ(img.apex_slope(), 0.0);
    }
  });
}

// The signed integrals from the tip are the quadratures of g and g'^2.
TEST(ShapesImage, IntegralsAreTheQuadratures) {
  for_each_example([&]([[maybe_unused]] const Indenter& ind, const auto& img) {
    const double a = img.contact_radius(0.01);
    auto g = [&](double x) { return img.g(x); };
    auto s2 = [&](double x) { return img.slope(x) * img.slope(x); };
    for (const auto& [l, r] : {std::pair{-a, a}, std::pair{-0.8 * a, -0.1 * a},
                               std::pair{0.2 * a, 0.9 * a}, std::pair{-0.3 * a, 0.6 * a}}) {
      const double I = integral(g, l, r), J = integral(s2, l, r);
      EXPECT_NEAR(img.integral_g(r) - img.integral_g(l), I, 1e-13 * integral(g, -a, a));
      EXPECT_NEAR(img.integral_slope_squared(r) - img.integral_slope_squared(l), J,
                  1e-13 * integral(s2, -a, a));
    }
  });
}

// The contact radius inverts g; its rate is its derivative in d; the elastic
// force is 4 G int (g(a) - g) over the contact, and the Hertz radius inverts it.
TEST(ShapesImage, RadiusAndElasticForceAreOfG) {
  for_each_example([&]([[maybe_unused]] const Indenter& ind, const auto& img) {
    const double d = 0.013, a = img.contact_radius(d), G = 2.5;
    EXPECT_NEAR(img.g(a), d, 4e-16 * d);
    EXPECT_NEAR(img.leading_edge(d), a, 4e-16 * a);
    EXPECT_TRUE(img.inside(0.99 * a, d));
    EXPECT_FALSE(img.inside(1.01 * a, d));
    const double hd = 1e-6 * d;
    const double rate = (img.contact_radius(d + hd) - img.contact_radius(d - hd)) / (2.0 * hd);
    EXPECT_NEAR(img.radius_rate(a, d), rate, 1e-8 * rate);
    const double F = 4.0 * G * integral([&](double x) { return d - img.g(x); }, -a, a);
    EXPECT_NEAR(img.elastic_force(a, G), F, 1e-13 * F);
    EXPECT_NEAR(img.hertz_radius(F, G), a, 1e-13 * a);
    EXPECT_DOUBLE_EQ(ind.elastic_force(a, G), img.elastic_force(a, G));
    EXPECT_DOUBLE_EQ(ind.contact_radius(d), img.contact_radius(d));
  });
}

// The forcing of a sub-step is u(t) = depth(x + w t, q(t)) on the sub-step:
// exactly where the image says so, else through u at 0, h/2 and h. (The
// row cuts a sub-step at the tip: each of these lies on one side of it.)
TEST(ShapesImage, ForcingFollowsTheDepthAlongTheSubStep) {
  for_each_example([&]([[maybe_unused]] const Indenter& ind, const auto& img) {
    const double a = img.contact_radius(0.01), w = 0.7, h = 0.05 * a / w;
    const Path q{0.01, 0.003, -0.02};
    for (const double x : {-0.9 * a, -0.3 * a, 0.1 * a, 0.6 * a}) {
      const auto f = img.template forcing<Forcing>(x, w, h, q);
      auto u = [&](double t) { return img.depth(x + w * t, q.at(t)); };
      for (const double t : {0.0, 0.5 * h, h})
        EXPECT_NEAR(f.at(t), u(t), 1e-14 * 0.01) << "x = " << x << ", t = " << t;
      if (img.exact_forcing()) {
        EXPECT_NEAR(f.at(h / 3.0), u(h / 3.0), 1e-14 * 0.01) << "x = " << x;
      }
    }
  });
}

} // namespace
} // namespace mdrmap
