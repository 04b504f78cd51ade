#include "erkn/ensemble.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <optional>
#include <thread>

#include "erkn/error.hpp"

namespace erkn {

Ensemble::Ensemble(const Method& method, double h, std::size_t size,
                   std::function<Member(std::size_t)> member, const Options& options)
    : method_(method), h_(h), size_(size), member_(std::move(member)), options_(options) {
  if (!member_) throw Error("Ensemble: the member function is not set");
}

Ensemble::Ensemble(const Method& method, double h, std::vector<Member> members,
                   const Options& options)
    : method_(method), h_(h), size_(members.size()), options_(options) {
  auto list = std::make_shared<const std::vector<Member>>(std::move(members));
  member_ = [list](std::size_t i) { return (*list)[i]; };
}

std::vector<TrajectoryResult> Ensemble::integrate(double t_end, int threads,
                                                  const Observer& observer) const {
  return integrate(t_end, 0, size_, threads, observer);
}

std::vector<TrajectoryResult> Ensemble::integrate(double t_end, std::size_t first, std::size_t last,
                                                  int threads, const Observer& observer) const {
  if (first > last || last > size_)
    throw Error("Ensemble: the range [" + std::to_string(first) + ", " + std::to_string(last) +
                ") is not within the " + std::to_string(size_) + " trajectories");
  if (threads < 0) throw Error("Ensemble: threads = " + std::to_string(threads) + " < 0");
  if (threads == 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t count = last - first;
  std::vector<TrajectoryResult> results(count);
  // Dynamic scheduling: each worker takes the next trajectory not yet started. Every trajectory
  // is computed by one thread alone, so the assignment cannot change a result.
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t k; (k = next.fetch_add(1)) < count;)
      results[k] = run(first + k, t_end, observer);
  };
  {
    std::vector<std::jthread> pool;  // joined at the end of this block
    const int workers = int(std::min<std::size_t>(std::size_t(threads), count));
    for (int w = 1; w < workers; ++w) pool.emplace_back(work);
    work();  // the calling thread is worker 0
  }
  return results;
}

namespace {

std::string message_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an exception of unknown type";
  }
}

}  // namespace

TrajectoryResult Ensemble::run(std::size_t i, double t_end, const Observer& observer) const {
  TrajectoryResult r;
  std::optional<Integrator> integrator;
  try {
    Member m = member_(i);
    r.q = m.q0;
    r.p = m.p0;
    integrator.emplace(method_, std::move(m.system), h_, m.q0, m.p0, options_);
    if (observer)
      integrator->integrate(t_end, [&](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
        observer(i, *integrator);
      });
    else
      integrator->integrate(t_end);
  } catch (...) {
    r.error = "trajectory " + std::to_string(i) + ": " + message_of(std::current_exception());
  }
  if (integrator) {
    r.q = integrator->q();
    r.p = integrator->p();
    r.t = integrator->t();
    r.statistics = integrator->statistics();
  }
  return r;
}

}  // namespace erkn
