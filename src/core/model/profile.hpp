#pragma once
// The indenter: a rigid axisymmetric profile and its MDR image g(x)
// (docs/design.md, "Indenter profiles"). Each shape is one class in one file
// of core/model/shapes/ (its name, its parameters with their ranges and help
// texts, and its image(): g, g', the contact radius, the elastic force and
// its radius, the kink at the tip and the integrals the element row needs);
// the table below lists them, and everything else asks the indenter (or
// visits its shape) instead of naming a shape.
#include <array>
#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

#include "core/model/shapes/cone.hpp"
#include "core/model/shapes/parabola.hpp"
#include "core/model/shapes/power.hpp"
#include "core/model/shapes/sphere.hpp"

namespace mdrmap {

/// The shapes, in the order of the help text; the first is the default.
using Shapes = std::tuple<Parabola, Cone, Power, Sphere>;
inline constexpr std::size_t kShapeCount = std::tuple_size_v<Shapes>;

template <class S, class T = Shapes> struct is_shape;
template <class S, class... T>
struct is_shape<S, std::tuple<T...>> : std::disjunction<std::is_same<S, T>...> {};
/// Whether S is one of the table's shapes.
template <class S> inline constexpr bool is_shape_v = is_shape<S>::value;

/// The MDR images of the shapes (a shape's image(): the parabola itself, the
/// cone's and the power law's g = c |x|^n), each type once: what the element
/// row holds and visits.
template <class V, class T> struct WithImage;
template <class... U, class T> struct WithImage<std::variant<U...>, T> {
  using type =
      std::conditional_t<(std::is_same_v<T, U> || ...), std::variant<U...>, std::variant<U..., T>>;
};
template <class V, class T> struct ImagesOf;
template <class V> struct ImagesOf<V, std::tuple<>> { using type = V; };
template <class V, class S, class... R> struct ImagesOf<V, std::tuple<S, R...>> {
  using image = std::decay_t<decltype(std::declval<S>().image())>;
  using type = typename ImagesOf<typename WithImage<V, image>::type, std::tuple<R...>>::type;
};
using ShapeImage = typename ImagesOf<std::variant<>, Shapes>::type;

/// Which shape an indenter has: its index in Shapes.
class Profile {
public:
  constexpr Profile() = default;
  template <class S> static constexpr Profile of() { return Profile(index_of<S>()); }
  constexpr std::size_t index() const { return i_; }
  constexpr bool operator==(Profile o) const { return i_ == o.i_; }
  constexpr bool operator!=(Profile o) const { return i_ != o.i_; }
  /// The shape numbered `i` (< kShapeCount).
  static constexpr Profile at(std::size_t i) { return Profile(i); }

private:
  constexpr explicit Profile(std::size_t i) : i_(i) {}
  template <class S, std::size_t I = 0> static constexpr std::size_t index_of() {
    if constexpr (std::is_same_v<S, std::tuple_element_t<I, Shapes>>)
      return I;
    else
      return index_of<S, I + 1>();
  }
  std::size_t i_ = 0;
};

/// Every kind, in the order of the table.
std::array<Profile, kShapeCount> all_profiles();

/// "parabola", "cone", "power", "sphere".
const char* profile_name(Profile p);
/// Parses a profile's name; throws InvalidInput("profile").
Profile parse_profile(const std::string& name);

/// The chosen shape and every shape's parameters: those of a shape not
/// chosen are 0 (not given), as the parameter table reads and sets them
/// whatever the profile, and validation refuses any given.
struct Indenter {
  Profile profile;
  Shapes shapes;

  /// visit() from the I-th shape on.
  template <std::size_t I, class F> decltype(auto) visit_from(F&& f) const {
    if constexpr (I + 1 == kShapeCount)
      return f(std::get<I>(shapes));
    else if (profile.index() == I)
      return f(std::get<I>(shapes));
    else
      return visit_from<I + 1>(std::forward<F>(f));
  }

  template <std::size_t I> ShapeImage image_from() const {
    if constexpr (I + 1 == kShapeCount)
      return ShapeImage(std::get<I>(shapes).image());
    else if (profile.index() == I)
      return ShapeImage(std::get<I>(shapes).image());
    else
      return image_from<I + 1>();
  }

  Indenter() = default;
  /// An indenter of shape s.
  template <class S, class = std::enable_if_t<is_shape_v<S>>>
  Indenter(const S& s) : profile(Profile::of<S>()) {
    std::get<S>(shapes) = s;
  }

  template <class S> bool is() const { return profile == Profile::of<S>(); }
  /// Shape S's parameters (whether or not it is the chosen one).
  template <class S> S& as() { return std::get<S>(shapes); }
  template <class S> const S& as() const { return std::get<S>(shapes); }
  /// f(shape) of the chosen shape (each shape's f returning the same type).
  template <class F> decltype(auto) visit(F&& f) const { return visit_from<0>(std::forward<F>(f)); }

  bool parabolic() const { return is<Parabola>(); }
  /// The chosen shape's image, formed once (its coefficient computed).
  ShapeImage image() const { return image_from<0>(); }
  /// The scale c of g (of g = c |x|^n: 1/R, (pi/2) tan(beta), kappa_n A), the
  /// element row's range checks' (core/model/row_limits.hpp).
  double coefficient() const {
    return visit([](const auto& s) { return s.image().coefficient(); });
  }
  double g(double x) const {
    return visit([x](const auto& s) { return s.image().g(x); });
  }
  double slope(double x) const {
    return visit([x](const auto& s) { return s.image().slope(x); });
  }
  /// Half-width a of the MDR contact at depth d: g(a) = d. (Inline: the
  /// solvers ask for it at every sample.)
  double contact_radius(double d) const {
    return visit([d](const auto& s) { return s.image().contact_radius(d); });
  }
  /// The same as the element-row solvers form it: sqrt(R d) for the parabola
  /// (their arithmetic since the seed, bit for bit), contact_radius otherwise.
  double leading_edge(double d) const {
    return visit([d](const auto& s) { return s.image().leading_edge(d); });
  }
  /// Elastic normal force of the full contact [-a, a] at depth g(a) on a
  /// foundation of modulus G: 4 G int (g(a) - g).
  double elastic_force(double a, double G) const {
    return visit([a, G](const auto& s) { return s.image().elastic_force(a, G); });
  }
  /// d ln F / d ln d of that force at depth d (dF/dd = 8 G a): (n + 1)/n
  /// for g = c |x|^n.
  double force_exponent(double d) const {
    return visit([d](const auto& s) { return s.image().force_exponent(d); });
  }
  /// The bound every contact radius stays below (the sphere's R; infinity).
  double max_radius() const {
    return visit([](const auto& s) { return s.image().max_radius(); });
  }
  /// The radius a of that force: elastic_force(a, G) = F.
  double hertz_radius(double F, double G) const {
    return visit([F, G](const auto& s) { return s.image().hertz_radius(F, G); });
  }
};

} // namespace mdrmap
