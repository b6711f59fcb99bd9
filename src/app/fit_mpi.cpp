#include "app/fit_mpi.hpp"

#include <stdexcept>

namespace mdrmap::app {
namespace {

/// A point's result on the wire: a flag (1 residuals, 0 refused, -1 an
/// error) and m values.
constexpr double kOk = 1.0, kRefused = 0.0, kError = -1.0;

} // namespace

std::vector<std::vector<double>>
MpiEvaluator::spread(const std::vector<std::vector<double>>& points, bool& stopped) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  const std::size_t n = p_.parameters().size(), m = p_.size(), w = m + 1;
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

  std::vector<double> mine;
  for (std::size_t k = static_cast<std::size_t>(rank); k < np;
       k += static_cast<std::size_t>(size)) {
    const std::vector<double> x(flat.begin() + static_cast<long>(k * n),
                                flat.begin() + static_cast<long>((k + 1) * n));
    std::vector<double> r;
    double flag = kOk;
    try {
      r = p_.residuals(x);
      if (r.size() != m) flag = kRefused;
    } catch (const std::exception&) {
      flag = kError;
    }
    mine.push_back(flag);
    r.resize(m, 0.0);
    mine.insert(mine.end(), r.begin(), r.end());
  }
  std::vector<int> counts(static_cast<std::size_t>(size)), displs(static_cast<std::size_t>(size));
  for (int q = 0, at = 0; q < size; ++q) {
    const std::size_t own =
        np > static_cast<std::size_t>(q)
            ? (np - static_cast<std::size_t>(q) + static_cast<std::size_t>(size) - 1) /
                  static_cast<std::size_t>(size)
            : 0;
    counts[static_cast<std::size_t>(q)] = static_cast<int>(own * w);
    displs[static_cast<std::size_t>(q)] = at;
    at += counts[static_cast<std::size_t>(q)];
  }
  std::vector<double> all(rank == 0 ? np * w : 0);
  MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
              displs.data(), MPI_DOUBLE, 0, comm_);
  if (rank != 0) return {};
  std::vector<std::vector<double>> out(np);
  for (int q = 0; q < size; ++q) {
    std::size_t at = static_cast<std::size_t>(displs[static_cast<std::size_t>(q)]);
    for (std::size_t k = static_cast<std::size_t>(q); k < np;
         k += static_cast<std::size_t>(size), at += w) {
      if (all[at] == kError)
        throw std::runtime_error("a model evaluation failed on rank " + std::to_string(q));
      if (all[at] == kOk)
        out[k].assign(all.begin() + static_cast<long>(at + 1),
                      all.begin() + static_cast<long>(at + w));
    }
  }
  return out;
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
