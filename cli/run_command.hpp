// `erkn run [options]`: the experiments (paper problems vs peers, charts, docs/results.md).
#pragma once

namespace erkn::cli {

/// Replaces this process by erkn-experiments with the same options (it lives in experiments/,
/// which may use Boost; the library and the rest of the CLI do not): the build tree's program
/// for the build tree's erkn, else the one installed beside this erkn.
int run_command(int argc, char** argv);

}  // namespace erkn::cli
