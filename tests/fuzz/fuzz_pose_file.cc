// init_pose.txt, rig_from_object.txt, gt poses: ReadPoseFile (bcot/core/pose_io.h).
#include "bcot/core/pose_io.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)bcot::ReadPoseFile(bcot::fuzz::ScratchFile("pose.txt", bcot::fuzz::Text(data, size)));
  return 0;
}
