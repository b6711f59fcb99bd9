#include "app/fit_mpi.hpp"

#include <stdexcept>

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)
namespace {

/// A point's result on the wire: a flag (1 residuals, 0 refused, -1 an
/// error) and m values.
constexpr double kOk = 1.0, kRefused = 0.0, kError = -1.0;

/// Who evaluates what of a batch: point k on rank k mod size.
struct Share {
  std::size_t rank, size, points, n, width; ///< width: a result's doubles (flag and m)
  std::size_t own(std::size_t q) const { return points > q ? (points - q + size - 1) / size : 0; }
};

/// This rank's results of the batch `flat` (points x n), one after another.
std::vector<double> evaluate_share(const FitProblem& p, const std::vector<double>& flat,
                                   const Share& s) {
  const std::size_t m = s.width - 1;
  std::vector<double> mine;
  for (std::size_t k = s.rank; k < s.points; k += s.size) {
    const std::vector<double> x(flat.begin() + static_cast<long>(k * s.n),
                                flat.begin() + static_cast<long>((k + 1) * s.n));
    std::vector<double> r;
    double flag = kOk;
    try {
      r = p.residuals(x);
      if (r.size() != m) flag = kRefused;
    } catch (const std::exception&) {
      flag = kError;
    }
    mine.push_back(flag);
    r.resize(m, 0.0);
    mine.insert(mine.end(), r.begin(), r.end());
  }
  return mine;
}

/// MPI_Gatherv's counts and displacements of the ranks' results.
void layout(const Share& s, std::vector<int>& counts, std::vector<int>& displs) {
  counts.assign(s.size, 0);
  displs.assign(s.size, 0);
  for (std::size_t q = 0, at = 0; q < s.size; ++q) {
    counts[q] = static_cast<int>(s.own(q) * s.width);
    displs[q] = static_cast<int>(at);
    at += s.own(q) * s.width;
  }
}

/// Rank 0: the gathered results in the batch's order (empty: refused).
/// Throws std::runtime_error where a rank's evaluation failed.
std::vector<std::vector<double>> unpack(const std::vector<double>& all, const Share& s,
                                        const std::vector<int>& displs) {
  std::vector<std::vector<double>> out(s.points);
  for (std::size_t q = 0; q < s.size; ++q) {
    auto at = static_cast<std::size_t>(displs[q]);
    for (std::size_t k = q; k < s.points; k += s.size, at += s.width) {
      if (all[at] == kError)
        throw std::runtime_error("a model evaluation failed on rank " + std::to_string(q));
      if (all[at] == kOk)
        out[k].assign(all.begin() + static_cast<long>(at + 1),
                      all.begin() + static_cast<long>(at + s.width));
    }
  }
  return out;
}

} // namespace

std::vector<std::vector<double>>
MpiEvaluator::spread(const std::vector<std::vector<double>>& points, bool& stopped) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  const std::size_t n = p_.parameters().size();
  long long count = static_cast<long long>(points.size());
  MPI_Bcast(&count, 1, MPI_LONG_LONG, 0, comm_);
  stopped = count == 0;
  if (stopped) return {};
  const auto np = static_cast<std::size_t>(count);
  std::vector<double> flat(np * n);
  if (rank == 0)
    for (std::size_t k = 0; k < np; ++k)
      for (std::size_t i = 0; i < n; ++i)
        flat[k * n + i] = points[k][i];
  MPI_Bcast(flat.data(), static_cast<int>(flat.size()), MPI_DOUBLE, 0, comm_);

  const Share share{static_cast<std::size_t>(rank), static_cast<std::size_t>(size), np, n,
                    p_.size() + 1};
  const std::vector<double> mine = evaluate_share(p_, flat, share);
  std::vector<int> counts, displs;
  layout(share, counts, displs);
  std::vector<double> all(rank == 0 ? np * share.width : 0);
  MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
              displs.data(), MPI_DOUBLE, 0, comm_);
  if (rank != 0) return {};
  return unpack(all, share, displs);
}

std::vector<std::vector<double>>
MpiEvaluator::evaluate(const std::vector<std::vector<double>>& points) {
  if (points.empty()) return {};
  bool stopped = false;
  return spread(points, stopped);
}

void MpiEvaluator::stop() {
  bool stopped = false;
  (void)spread({}, stopped);
}

void MpiEvaluator::serve() {
  bool stopped = false;
  while (!stopped)
    (void)spread({}, stopped);
}

} // namespace mdrmap::app
