// The FFTW wisdom file shared by processes (ERKN_FFTW_WISDOM, runtime/src/fftw_backend.cpp): each
// new plan of a process first imports what other processes wrote to the file since, so every
// process plans a size as the first one to plan it did, and keeps their plans in the file. Another
// process is played here by FFTW itself: a plan made and exported to the file, then forgotten
// (fftw_forget_wisdom), so only the file knows it. Negative control: with ERKN_FFTW_WISDOM unset a
// new plan neither reads nor writes the file.
#include <fftw3.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "grid_backend.hpp"

namespace erkn::test {
namespace {

using erkn::GridAxis;

// The plans of a wisdom text, one per line (without the header line naming FFTW's version).
std::set<std::string> plan_lines(const std::string& wisdom) {
  std::set<std::string> out;
  std::istringstream in(wisdom);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("  (", 0) == 0) out.insert(line);
  return out;
}

std::string read(const std::string& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), {}};
}

// "Another process's" plan of a complex DFT of n points (a transform erkn never plans), written
// to file and forgotten by this process; returns its wisdom.
std::string other_process_writes(const std::string& file, int n) {
  fftw_complex* a = fftw_alloc_complex(std::size_t(n));
  fftw_plan plan = fftw_plan_dft_1d(n, a, a, FFTW_FORWARD, FFTW_MEASURE);
  char* text = fftw_export_wisdom_to_string();
  const std::string wisdom(text);
  fftw_free(text);
  fftw_destroy_plan(plan);
  fftw_free(a);
  fftw_forget_wisdom();
  std::ofstream(file) << wisdom;
  return wisdom;
}

// A periodic grid of n1 x n2 points no other test plans (the plans are kept for the process).
void plan_grid(Eigen::Index n1, Eigen::Index n2) {
  using B = GridAxis::Boundary;
  detail::make_half_spectrum_backend({{n1, 0.5, B::periodic}, {n2, 0.25, B::periodic}});
}

TEST(FftwWisdom, EachNewPlanImportsWhatOtherProcessesWroteSince) {
  const std::string file = testing::TempDir() + "erkn_wisdom_" + std::to_string(getpid());
  ASSERT_EQ(setenv("ERKN_FFTW_WISDOM", file.c_str(), 1), 0);
  // Twice: the second plan comes after this process has imported the file once.
  for (auto [n, n1, n2] : {std::tuple{12, 6, 14}, std::tuple{20, 6, 18}}) {
    const std::set<std::string> theirs = plan_lines(other_process_writes(file, n));
    ASSERT_FALSE(theirs.empty());
    plan_grid(n1, n2);
    const std::set<std::string> after = plan_lines(read(file));
    for (const std::string& line : theirs) EXPECT_TRUE(after.count(line)) << n << ": " << line;
    EXPECT_GT(after.size(), theirs.size()) << "the grid's plans were not added to the file";
  }
  // Negative control: without ERKN_FFTW_WISDOM the file is neither read nor rewritten.
  ASSERT_EQ(unsetenv("ERKN_FFTW_WISDOM"), 0);
  const std::string theirs = other_process_writes(file, 28);
  plan_grid(6, 22);
  EXPECT_EQ(read(file), theirs);
  std::remove(file.c_str());
}

}  // namespace
}  // namespace erkn::test
