// Where one volrender process's time goes: named milestones in milliseconds since the process started (its static
// initialisation), for the --stats JSON. The whole process's wall time minus the last milestone is its exit.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace vr {

// Records `milestone` now (any thread); a milestone marked again keeps its first time.
void markMilestone(const std::string& milestone);

// Every milestone so far, by name.
nlohmann::json processTimeline();

}  // namespace vr
