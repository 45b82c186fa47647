// framework/media: PNG files through libpng and video frames through libav, which replaced OpenCV's
// imgcodecs and videoio in the product (issue 31, session 17: those two modules loaded about 240 shared
// libraries at every start of `crowdlab`). The tests still link OpenCV's readers, so each case checks the
// new code against what OpenCV gives for the same file.
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/media/png_image.hpp"
#include "framework/media/video_reader.hpp"
#include "stimuli/video_encoder.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_media_files {

using namespace crowdlab;

namespace {

/// A deterministic pattern with every channel different, so a swapped channel order shows.
cv::Mat pattern(int rows, int cols, int type) {
  cv::Mat m(rows, cols, type);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols * m.channels(); ++c)
      m.ptr<std::uint8_t>(r)[c] =
          static_cast<std::uint8_t>((r * 37 + c * 11 + (c % m.channels()) * 60) % 256);
  return m;
}

void write_bytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

/// A short H.264 clip of moving colour bars, written by the stimuli's own encoder.
std::filesystem::path write_clip(const std::filesystem::path& dir, int frames) {
  const auto path = dir / "bars.mp4";
  stimuli::VideoSettings settings;
  settings.width = 64, settings.height = 48, settings.fps = 25.0, settings.crf = 10;
  stimuli::VideoEncoder encoder(path.string(), settings);
  std::vector<std::uint8_t> rgba(64 * 48 * 4);
  for (int f = 0; f < frames; ++f) {
    for (int i = 0; i < 64 * 48; ++i) {
      const int x = (i % 64 + 3 * f) % 64;
      rgba[4 * i + 0] = static_cast<std::uint8_t>(x < 21 ? 230 : 20);
      rgba[4 * i + 1] = static_cast<std::uint8_t>(x >= 21 && x < 42 ? 200 : 30);
      rgba[4 * i + 2] = static_cast<std::uint8_t>(x >= 42 ? 210 : 40);
      rgba[4 * i + 3] = 255;
    }
    encoder.add_frame(rgba.data(), false);
  }
  encoder.close();
  return path;
}

}  // namespace

TEST_CASE("write_png_file keeps every pixel of strided rows, and writes OpenCV's bytes", "[media]") {
  const auto dir = test::scratch_dir("media_png");
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4}) {
    // A region of a wider image: rows are not packed, as in a cv::Mat view.
    const cv::Mat wide = pattern(23, 41, type);
    const cv::Mat image = wide(cv::Rect(3, 2, 31, 19));
    REQUIRE_FALSE(image.isContinuous());
    const auto path = dir / ("p" + std::to_string(image.channels()) + ".png");
    write_png_file(path.string(), image.data, image.cols, image.rows, image.channels(), image.step);
    const cv::Mat back = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    REQUIRE(back.type() == image.type());
    CHECK(back.size() == image.size());
    CHECK(cv::norm(back, image, cv::NORM_INF) == 0.0);
  }
  // The same settings as OpenCV's encoder (zlib level 1, run-length, Sub filter): the same bytes.
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4}) {
    const cv::Mat image = pattern(29, 37, type);
    std::vector<std::uint8_t> theirs;
    REQUIRE(cv::imencode(".png", image, theirs));
    CHECK(encode_png(image.data, image.cols, image.rows, image.channels(), image.step) == theirs);
  }
}

TEST_CASE("encode_png and write_png_file refuse what they cannot do, naming the file", "[media]") {
  const auto dir = test::scratch_dir("media_png_bad");
  const cv::Mat two = pattern(4, 4, CV_8UC2);
  CHECK_THROWS_AS(encode_png(two.data, 4, 4, 2, two.step), InputError);
  const cv::Mat three = pattern(4, 4, CV_8UC3);
  CHECK_THROWS_AS(encode_png(three.data, 4, 4, 3, 11), InputError);  // rows shorter than 4 pixels
  CHECK_THROWS_AS(encode_png(three.data, 0, 4, 3, three.step), InputError);
  const auto unwritable = dir / "no-such-folder" / "frame.png";
  CHECK_THROWS_WITH(write_png_file(unwritable.string(), three.data, 4, 4, 3, three.step),
                    Catch::Contains("frame.png"));
}

TEST_CASE("VideoReader gives every frame of an H.264 clip, as OpenCV's reader did", "[media]") {
  const auto dir = test::scratch_dir("media_video");
  const auto clip = write_clip(dir, 12);
  VideoReader reader(clip.string());
  CHECK(reader.width() == 64);
  CHECK(reader.height() == 48);
  CHECK(reader.fps() == Approx(25.0));
  CHECK(reader.frame_count_estimate() == 12);

  cv::VideoCapture opencv(clip.string(), cv::CAP_FFMPEG);
  REQUIRE(opencv.isOpened());
  int frames = 0;
  double worst = 0.0;
  while (reader.next()) {
    cv::Mat ours(reader.height(), reader.width(), CV_8UC3), luma(reader.height(), reader.width(), CV_8UC1);
    reader.copy_bgr(ours.data, ours.step);
    reader.copy_luma(luma.data, luma.step);
    cv::Mat theirs;
    REQUIRE(opencv.read(theirs));
    worst = std::max(worst, cv::norm(ours, theirs, cv::NORM_INF));
    // The bars are where they were drawn: red on the left of frame 0 (BGR order), blue on the right.
    if (frames == 0) {
      CHECK(ours.at<cv::Vec3b>(24, 5)[2] > 180);
      CHECK(ours.at<cv::Vec3b>(24, 5)[0] < 90);
      CHECK(ours.at<cv::Vec3b>(24, 58)[0] > 160);
    }
    CHECK(cv::mean(luma)[0] > 16.0);
    ++frames;
  }
  CHECK(frames == 12);
  cv::Mat extra;
  CHECK_FALSE(opencv.read(extra));
  // The same decoder and the same bicubic conversion: at most a rounding step apart.
  CHECK(worst <= 2.0);
  CHECK_FALSE(reader.next());  // and it stays at the end
}

TEST_CASE("VideoReader refuses a file that is not a video, naming it", "[media]") {
  const auto dir = test::scratch_dir("media_video_bad");
  write_bytes(dir / "noise.mp4", std::vector<std::uint8_t>(4096, 0x5a));
  CHECK_THROWS_WITH(VideoReader((dir / "noise.mp4").string()), Catch::Contains("noise.mp4"));
  CHECK_THROWS_AS(VideoReader((dir / "absent.mp4").string()), RuntimeError);
}

}  // namespace test_media_files
