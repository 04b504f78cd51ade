// erkn stability: the stability regions of paper §4.1 as CSV grids and gnuplot charts.
#pragma once

namespace erkn::cli {

/// argv[0] is "stability". Returns the process exit code; throws erkn::Error on bad input.
int stability_command(int argc, char** argv);

}  // namespace erkn::cli
