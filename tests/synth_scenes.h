// Small synthetic scenes that tests render in process with Synthesize(). Header-only: the layer
// test binaries that include it link synth.
#pragma once

#include "bcot/synth/synth_options.h"

namespace bcot::test {

// Two cameras 90° apart (cam0, cam1) of width×height pixels, `num_frames` frames, no distractors
// and one background sample per pixel; every other option keeps its default.
inline SynthOptions SmallBinocularSynthOptions(int width, int height, int num_frames) {
  SynthOptions options;
  options.cameras.width = width;
  options.cameras.height = height;
  options.cameras.arc_angles_deg = {90};
  options.motion.num_frames = num_frames;
  options.distractors.count = 0;
  options.render.background_samples_per_axis = 1;
  return options;
}

}  // namespace bcot::test
