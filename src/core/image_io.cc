#include "bcot/core/image_io.h"

#include <fmt/format.h>
#include <jpeglib.h>

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "bcot/core/file_util.h"

namespace bcot {
namespace {

// Lower-case extension of `path` with the dot ("" when none).
std::string Extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// libjpeg and libpng decode a truncated file without an error (the missing rows come out grey
// or black, with at most a warning on stderr), so check the end of the stream before decoding:
// a JPEG ends with the EOI marker FF D9 (some writers pad after it), a PNG with the IEND chunk.
Status CheckCompleteImageFile(const std::string& path, const std::vector<unsigned char>& bytes) {
  const std::string extension = Extension(path);
  if (extension == ".jpg" || extension == ".jpeg") {
    size_t end = bytes.size();
    while (end > 2 && bytes[end - 1] == 0) --end;  // zero padding after EOI
    if (end < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8 || bytes[end - 2] != 0xFF ||
        bytes[end - 1] != 0xD9) {
      return Status::InvalidInput(path + ": corrupt JPEG (truncated: no end-of-image marker)");
    }
  } else if (extension == ".png") {
    static const unsigned char kIend[] = {'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    if (bytes.size() < 8 + 12 ||
        !std::equal(std::begin(kIend), std::end(kIend), bytes.end() - sizeof(kIend))) {
      return Status::InvalidInput(path + ": corrupt PNG (truncated: no IEND chunk at the end)");
    }
  }
  return Status::Ok();
}

// libjpeg reports a fatal error through error_exit, which must not return (its default exits
// the process): jump back into ReadJpeg.
struct JpegErrorManager {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
};

[[noreturn]] void JumpOnJpegError(j_common_ptr info) {
  std::longjmp(reinterpret_cast<JpegErrorManager*>(info->err)->jump, 1);
}

// True when the APP1 markers libjpeg saved hold an Exif block (which may rotate the image).
bool HasExif(const jpeg_decompress_struct& info) {
  for (jpeg_saved_marker_ptr marker = info.marker_list; marker != nullptr; marker = marker->next) {
    if (marker->marker == JPEG_APP0 + 1 && marker->data_length >= 6 &&
        std::memcmp(marker->data, "Exif\0\0", 6) == 0) {
      return true;
    }
  }
  return false;
}

// What ReadJpeg reads of a JPEG: the frame header only, or the pixels too.
enum class JpegRead { kHeader, kPixels };

// Reads the JPEG in `bytes` with libjpeg. Always its header: `*sampling` (when not null) is its
// chroma's sampling relative to luma (the coarsest of its chroma components). With kPixels also its
// pixels, straight into BGR rows (libjpeg-turbo's JCS_EXT_BGR output): the pixels of
// cv::imdecode(IMREAD_COLOR) — the same library, the same default IDCT and upsampling — without
// OpenCV's RGB-to-BGR pass, which costs as much again as the decode (scripts/bench_image_read.sh,
// 960×768: 2.1 against 4.7 ms). False on a libjpeg error (a CMYK file, corrupt headers) and, with
// kPixels, on an Exif block: the decode is then left to cv::imdecode, which reports or handles the
// first and turns the image by the second's orientation tag. Warnings about corrupt data go to
// stderr as under imdecode. Only trivially destructible locals live across setjmp.
bool ReadJpeg(const std::vector<unsigned char>& bytes, JpegRead read, ChromaSampling* sampling,
              cv::Mat3b* image) {
  jpeg_decompress_struct info;
  JpegErrorManager errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = JumpOnJpegError;
  if (setjmp(errors.jump) != 0) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_save_markers(&info, JPEG_APP0 + 1, 0xFFFF);
  jpeg_read_header(&info, TRUE);
  if (sampling != nullptr) {
    *sampling = ChromaSampling::Full();
    // Sampling factors are 1..4 (libjpeg rejects others); luma has the largest.
    for (int c = 1; c < info.num_components; ++c) {
      sampling->horizontal =
          std::max(sampling->horizontal, info.max_h_samp_factor / info.comp_info[c].h_samp_factor);
      sampling->vertical =
          std::max(sampling->vertical, info.max_v_samp_factor / info.comp_info[c].v_samp_factor);
    }
  }
  if (read == JpegRead::kHeader || HasExif(info)) {
    jpeg_destroy_decompress(&info);
    return read == JpegRead::kHeader;
  }
  info.out_color_space = JCS_EXT_BGR;
  jpeg_start_decompress(&info);
  image->create(static_cast<int>(info.output_height), static_cast<int>(info.output_width));
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = image->ptr(static_cast<int>(info.output_scanline));
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return true;
}

// The bytes of the image file at `path`; kInvalidInput naming it when it cannot be read.
StatusOr<std::vector<unsigned char>> ReadImageBytes(const std::string& path) {
  const StatusOr<std::string> file = ReadFileContents(path);
  if (!file.ok()) {
    return Status::InvalidInput(path + ": cannot read the image (" + file.status().message() + ")");
  }
  return std::vector<unsigned char>(file->begin(), file->end());
}

// Whether `bytes` start like a JPEG (SOI marker, then a marker).
bool IsJpeg(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

}  // namespace

StatusOr<ChromaSampling> ReadChromaSampling(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::vector<unsigned char> bytes, ReadImageBytes(path));
  if (!IsJpeg(bytes)) return ChromaSampling::Full();
  ChromaSampling sampling;
  if (!ReadJpeg(bytes, JpegRead::kHeader, &sampling, nullptr)) {
    return Status::InvalidInput(path + ": corrupt JPEG header");
  }
  return sampling;
}

StatusOr<cv::Mat3b> ReadColorImage(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::vector<unsigned char> bytes, ReadImageBytes(path));
  if (bytes.empty()) return Status::InvalidInput(path + ": cannot read the image (empty file)");
  BCOT_RETURN_IF_ERROR(CheckCompleteImageFile(path, bytes));
  cv::Mat3b jpeg;
  if (IsJpeg(bytes) && ReadJpeg(bytes, JpegRead::kPixels, nullptr, &jpeg)) return jpeg;
  const cv::Mat image = cv::imdecode(bytes, cv::IMREAD_COLOR);
  if (image.empty()) return Status::InvalidInput(path + ": cannot read the image");
  return cv::Mat3b(image);
}

StatusOr<cv::Mat3b> ReadCameraImage(const std::string& path, const Camera& camera) {
  BCOT_ASSIGN_OR_RETURN(cv::Mat3b image, ReadColorImage(path));
  if (image.cols != camera.width || image.rows != camera.height) {
    return Status::InvalidInput(fmt::format("{}: image is {}x{}, camera '{}' in rig.yaml is {}x{}",
                                            path, image.cols, image.rows, camera.name, camera.width,
                                            camera.height));
  }
  return image;
}

}  // namespace bcot
