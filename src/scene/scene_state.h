// scene_state.h - a scene (and a target) in the byte stream of a checkpoint,
// so that a checkpoint resumes without its scene file. Mesh targets keep the
// path that was read; they are read again on resuming.
#pragma once
#include "core/state_io.h"
#include "scene/scene.h"

namespace ff {

void writeTargetState(StateWriter& w, const TargetSpec& t);
TargetSpec readTargetState(StateReader& r);
void writeSceneState(StateWriter& w, const SceneDesc& s);
SceneDesc readSceneState(StateReader& r);

}  // namespace ff
