// The run's verdict in sentences (written to summary.md and at the top of results.md): where the
// best paper method wins and loses against the exact-flow peers and the other peers, whether the
// targets are met, what is intrinsic where the paper's methods stay above the target, and who
// survives the stiff scene. Every number comes from the run; docs/performance.md points to it.
#pragma once

#include <string>
#include <vector>

#include "stiff_scene.hpp"
#include "summary.hpp"

namespace ex {

std::string verdict_markdown(const std::vector<SceneRuns>& scenes,
                             const std::vector<StiffResult>& stiff);

}  // namespace ex
