// Pose text files in BCOT's format: one pose per line,
//   r11 r12 r13 r21 r22 r23 r31 r32 r33 tx ty tz
// (R row-major, t in mm) meaning X_target = R·X_source + t. Readers accept tabs or spaces,
// a trailing separator, CRLF line ends and blank trailing lines; rotations must be
// orthonormal within 1e-4 (BCOT stores 6-8 digits) and are re-orthonormalised on read.
// Writers print the shortest decimal that reads back to the same double, so a written pose
// reads back bit-exact (a rotation already orthonormal to 1e-12 is kept as is).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/status.h"

namespace bcot {

// Largest deviation max|RᵀR − I| accepted when reading a rotation from a file.
inline constexpr double kRotationReadTolerance = 1e-4;

// Shared by every reader of rotations (pose files, rig.yaml): false (with the reason in `why`)
// when `rotation` is not a rotation within kRotationReadTolerance; otherwise replaces it by the
// nearest rotation, leaving it untouched when it is already orthonormal to 1e-12.
bool OrthonormalizeReadRotation(Eigen::Matrix3d* rotation, std::string* why);

// `context` prefixes error messages, normally "file:line".
StatusOr<Eigen::Isometry3d> ParsePoseLine(const std::string& line, const std::string& context);

// One line, tab separated, no trailing separator, no newline. Each number is the shortest
// decimal that reads back to the same double (e.g. "0.5", "1e-07", "0.30000000000000004"),
// so WritePoseFile → ReadPoseFile is lossless.
std::string FormatPoseLine(const Eigen::Isometry3d& target_from_source);

// One pose per line (line i = pose i); blank lines are allowed only after the last pose,
// since a blank line in the middle would shift every later frame. Errors name the file and
// the 1-based line number.
StatusOr<std::vector<Eigen::Isometry3d>> ReadPoseFile(const std::string& path);

// The same rules for lines[first...] of a file `path` whose earlier lines are a header (RBOT's
// pose files); messages name `path` and the 1-based line.
StatusOr<std::vector<Eigen::Isometry3d>> ParsePoseLines(const std::vector<std::string>& lines,
                                                        size_t first, const std::string& path);

// Writes one line per pose (LF line ends) atomically.
Status WritePoseFile(const std::string& path, const std::vector<Eigen::Isometry3d>& poses);

}  // namespace bcot
