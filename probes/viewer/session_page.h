#pragma once
// Writes the self-contained session page: one HTML file holding three.js and
// its OrbitControls (copied from Debian's libjs-three), the page script
// (viewer.js), and the session as JSON: scene meshes (primitives tessellated,
// half-spaces as a square), the tool mesh in its frame T, and per frame the
// device pose, the simulated tool pose, the recorded wrench and the contact
// points. Nothing is fetched at view time.
#include <iosfwd>
#include <string>

#include "haptics/scene/build_scene.h"
#include "haptics/scene/scene_config.h"
#include "probes/viewer/rerender_session.h"
#include "probes/viewer/session_data.h"

namespace probes {

struct PageOptions {
  std::string three_dir = "/usr/share/javascript/three";  // libjs-three
  int max_frames = 5000;  // frames kept in the page (every k-th pose); <= 0: all
};

// Throws InputError if three.js cannot be read from options.three_dir.
void WriteSessionPage(std::ostream& out, const haptics::SceneConfig& config,
                      const haptics::SceneModels& models, const Session& session,
                      const RerenderedSession& rerendered, const PageOptions& options);

}  // namespace probes
