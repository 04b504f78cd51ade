// erkn advise: the step-size advisor (erkn/advisor.hpp) from the command line.
#pragma once

namespace erkn::cli {

/// argv[0] is "advise". Exit code 0: h is not flagged; 3: flagged (the report says why and
/// suggests the nearest h without findings). Throws erkn::Error on bad input.
int advise_command(int argc, char** argv);

}  // namespace erkn::cli
