#pragma once
// Private to the study runner: collective error handling, and the checks made
// before a study writes anything (the output path, a resume's map and config,
// the memory of this node, the space on the map's file system).
#include <mpi.h>

#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "core/solvers/dispatch.hpp"
#include "io/map_file.hpp"
#include "study/case_source.hpp"
#include "study/config.hpp"
#include "study/runner.hpp"

namespace mdrmap::study::detail {

/// Runs fn on every rank; if it throws anywhere, every rank throws the error
/// of the lowest failing rank (InvalidInput stays InvalidInput, anything else
/// becomes CollectiveFailure), so no rank is left waiting in a collective call.
template <class F> void collectively(MPI_Comm comm, F fn) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int kind = 0; // 0 ok, 1 InvalidInput, 2 other
  std::string option, message;
  try {
    fn();
  } catch (const InvalidInput& e) {
    kind = 1, option = e.option(), message = e.what();
  } catch (const std::exception& e) {
    kind = 2, message = e.what();
  }
  int mine = kind ? rank : 1 << 30, first = 0;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == 1 << 30) return;
  auto bcast_string = [&](std::string& s) {
    int n = static_cast<int>(s.size());
    MPI_Bcast(&n, 1, MPI_INT, first, comm);
    s.resize(static_cast<std::size_t>(n));
    MPI_Bcast(s.data(), n, MPI_CHAR, first, comm);
  };
  MPI_Bcast(&kind, 1, MPI_INT, first, comm);
  bcast_string(option);
  bcast_string(message);
  if (kind == 1) throw InvalidInput(option, message);
  throw CollectiveFailure(message);
}

/// Rank 0's s on every rank (collective).
std::string bcast_from_root(MPI_Comm comm, std::string s);
/// Rank 0's v on every rank (collective).
void bcast_from_root(MPI_Comm comm, std::vector<std::uint64_t>& v);

/// The directory a path's file is in ("." for a bare name).
std::string parent_dir(const std::string& path);

/// The map a study of n_cases cases needs: its shape, the case parameters it
/// stores, and a grid's axes with their units and meanings.
io::MapSpec map_spec(const StudyConfig& cfg, std::size_t n_cases);

/// Unit and meaning of a grid axis: its column's entry of the core's table
/// (or a segment's velocity or duration, or a ratio).
io::FieldInfo axis_info(const Axis& a);

/// What the checks established, alike on every rank.
struct StudyPlan {
  SolverKind kind = SolverKind::Auto;
  std::optional<CaseSource> cases; ///< the cases by index (refers to the request's config)
  std::string canon;               ///< canonical(config), stored in the map and compared on resume
  io::MapSpec spec;                ///< the map the study needs
};

/// Collective. Parses the solver, refuses a study too large for this node's
/// memory, checks every case as expand_cases does without storing them (a
/// grid's cases split among the ranks, a case list read by rank 0, which
/// sends the others its index); rank 0 checks the output path and, on
/// resume, that the map holds this study, or else that a new map fits on its
/// file system. Throws InvalidInput on every rank alike.
StudyPlan preflight(MPI_Comm comm, const StudyRequest& req);

} // namespace mdrmap::study::detail
