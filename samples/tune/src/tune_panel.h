#pragma once
// `s3d tune`'s side panel: edits the session's state (a copy of the settings is validated before it is taken)
// and shows the frame's numbers.
#include <string>

#include "s3d/tune/tune_session.h"
#include "s3d/tune/tune_state.h"

namespace s3d::tune {

// The panel's own state (text fields, messages) besides TuneState.
struct PanelState {
  char profilePath[512] = "comfort_profile.json";
  std::string message;  // the last profile action or rejected edit
};

void drawPanel(TuneSession& session, TuneState& state, const FrameNumbers& numbers, PanelState& panel,
               const std::string& deviceName, float frameSeconds);

}  // namespace s3d::tune
