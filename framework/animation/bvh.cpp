#include "framework/animation/bvh.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/printable_excerpt.hpp"

namespace crowdlab {

namespace {

std::string format_number(double v) {
  std::ostringstream ss;
  ss << v;
  return ss.str();
}

struct Token {
  std::string text;
  int line = 0, column = 0;
};

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> out;
  int line = 1, column = 1;
  // A UTF-8 byte-order mark (Windows editors write one) is not part of the first keyword: it was
  // reported as "expected 'HIERARCHY', found 'HIERARCHY'" (issue 33).
  size_t i = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line, column = 1, ++i;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++column, ++i;
      continue;
    }
    Token t{{}, line, column};
    if (c == '{' || c == '}') {
      t.text = std::string(1, c);
      ++i, ++column;
    } else {
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != '{' &&
             text[i] != '}')
        t.text += text[i++], ++column;
    }
    out.push_back(std::move(t));
  }
  return out;
}

class Parser {
 public:
  Parser(const std::string& text, std::string source) : tokens_(tokenize(text)), source_(std::move(source)) {}

  BvhMotion parse() {
    BvhMotion m;
    m.source = source_;
    expect("HIERARCHY");
    expect("ROOT");
    parse_joint(m, -1, 1);
    if (peek_is("ROOT")) fail(peek(), "multiple ROOT hierarchies are not supported");
    expect("MOTION");
    expect("Frames:");
    const Token& frames_tok = peek();
    const double frames = number("frame count");
    if (frames < 0 || frames != std::floor(frames) || frames > 1e8)
      fail(frames_tok, "Frames: must be a non-negative integer");
    m.frame_count = static_cast<int>(frames);
    expect("Frame");
    expect("Time:");
    const Token& time_tok = peek();
    m.frame_time_s = number("frame time");
    if (!(m.frame_time_s >= kMinBvhFrameTime_s && m.frame_time_s <= kMaxBvhFrameTime_s))
      fail(time_tok, "Frame Time: must be between " + format_number(kMinBvhFrameTime_s) + " and " +
                         format_number(kMaxBvhFrameTime_s) + " seconds, got '" + time_tok.text + "'");
    const size_t expected = static_cast<size_t>(m.frame_count) * static_cast<size_t>(m.channel_count);
    // Never allocate from the header alone: the file holds at most one value per remaining token.
    m.values.reserve(std::min(expected, tokens_.size() - pos_));
    while (pos_ < tokens_.size()) {
      if (m.values.size() == expected)
        fail(peek(), "more motion values than Frames: " + std::to_string(m.frame_count) + " x " +
                         std::to_string(m.channel_count) + " channels");
      m.values.push_back(number("motion value"));
    }
    if (m.values.size() != expected) {
      const Token last = tokens_.empty() ? Token{"", 1, 1} : tokens_.back();
      fail(last, "truncated MOTION section: expected " + std::to_string(expected) + " values (" +
                     std::to_string(m.frame_count) + " frames x " + std::to_string(m.channel_count) +
                     " channels), got " + std::to_string(m.values.size()) + " (frame " +
                     std::to_string(m.values.size() / std::max(1, m.channel_count)) + " incomplete)");
    }
    if (m.joints.empty()) fail(Token{"", 1, 1}, "no joints");
    return m;
  }

 private:
  [[noreturn]] void fail(const Token& t, const std::string& msg) const {
    throw InputError(SourceLocation{source_, t.line, t.column, ""}, msg);
  }
  const Token& peek() const {
    if (pos_ >= tokens_.size()) {
      static Token end;
      end = tokens_.empty() ? Token{"", 1, 1} : tokens_.back();
      fail(end, "unexpected end of file");
    }
    return tokens_[pos_];
  }
  bool peek_is(const std::string& s) const { return pos_ < tokens_.size() && tokens_[pos_].text == s; }
  const Token& next() {
    const Token& t = peek();
    ++pos_;
    return t;
  }
  void expect(const std::string& s) {
    const Token& t = next();
    if (t.text != s) fail(t, "expected '" + s + "', found " + quote_value(t.text));
  }
  double number(const std::string& what) {
    const Token& t = next();
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(t.text.c_str(), &end);
    if (t.text.empty() || end != t.text.c_str() + t.text.size() || errno == ERANGE)
      fail(t, "expected a number for the " + what + ", found " + quote_value(t.text));
    if (!std::isfinite(v)) fail(t, "the " + what + " is not finite ('" + t.text + "')");
    return v;
  }
  Vec3 vec3(const std::string& what) {
    const double x = number(what), y = number(what), z = number(what);
    return {x, y, z};
  }
  BvhChannel channel(const Token& t) {
    static const std::pair<const char*, BvhChannel> names[] = {
        {"Xposition", BvhChannel::kXposition}, {"Yposition", BvhChannel::kYposition},
        {"Zposition", BvhChannel::kZposition}, {"Xrotation", BvhChannel::kXrotation},
        {"Yrotation", BvhChannel::kYrotation}, {"Zrotation", BvhChannel::kZrotation}};
    for (const auto& [n, c] : names)
      if (t.text == n) return c;
    fail(t, "unknown channel '" + t.text + "'");
  }

  void parse_joint(BvhMotion& m, int parent, int depth) {
    const Token& name_tok = next();
    if (depth > kMaxBvhJointDepth)
      fail(name_tok, "joints nest more than " + std::to_string(kMaxBvhJointDepth) +
                         " levels deep (a human skeleton needs fewer than 30)");
    if (name_tok.text == "{") fail(name_tok, "joint name missing");
    BvhJoint j;
    j.name = name_tok.text;
    // Names may contain spaces in some exporters: join tokens up to '{'.
    while (!peek_is("{")) j.name += " " + next().text;
    j.parent = parent;
    j.line = name_tok.line;
    expect("{");
    expect("OFFSET");
    j.offset = vec3("OFFSET of joint '" + j.name + "'");
    expect("CHANNELS");
    const Token& count_tok = peek();
    const double count = number("channel count");
    if (count < 0 || count > 6 || count != std::floor(count)) fail(count_tok, "CHANNELS count must be 0-6");
    for (int c = 0; c < static_cast<int>(count); ++c) j.channels.push_back(channel(next()));
    j.first_channel = m.channel_count;
    m.channel_count += static_cast<int>(count);
    const int index = static_cast<int>(m.joints.size());
    m.joints.push_back(j);
    for (;;) {
      const Token& t = next();
      if (t.text == "}") return;
      if (t.text == "JOINT") {
        parse_joint(m, index, depth + 1);
      } else if (t.text == "End") {
        expect("Site");
        expect("{");
        expect("OFFSET");
        m.joints[static_cast<size_t>(index)].end_site = vec3("End Site OFFSET");
        m.joints[static_cast<size_t>(index)].has_end_site = true;
        expect("}");
      } else {
        fail(t, "expected JOINT, End Site or '}' in joint '" + j.name + "', found " + quote_value(t.text));
      }
    }
  }

  std::vector<Token> tokens_;
  std::string source_;
  size_t pos_ = 0;
};

}  // namespace

RigidTransform BvhMotion::local_transform(int joint, int frame) const {
  const BvhJoint& j = joints[static_cast<size_t>(joint)];
  RigidTransform t;
  t.translation = j.offset;
  const double* v = values.data() + static_cast<size_t>(frame) * static_cast<size_t>(channel_count) +
                    static_cast<size_t>(j.first_channel);
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  for (size_t c = 0; c < j.channels.size(); ++c) {
    switch (j.channels[c]) {
      case BvhChannel::kXposition:
        t.translation.x() = v[c];
        break;
      case BvhChannel::kYposition:
        t.translation.y() = v[c];
        break;
      case BvhChannel::kZposition:
        t.translation.z() = v[c];
        break;
      case BvhChannel::kXrotation:
        t.rotation = t.rotation * Quat(Eigen::AngleAxisd(v[c] * kDeg, Vec3::UnitX()));
        break;
      case BvhChannel::kYrotation:
        t.rotation = t.rotation * Quat(Eigen::AngleAxisd(v[c] * kDeg, Vec3::UnitY()));
        break;
      case BvhChannel::kZrotation:
        t.rotation = t.rotation * Quat(Eigen::AngleAxisd(v[c] * kDeg, Vec3::UnitZ()));
        break;
    }
  }
  t.rotation.normalize();
  return t;
}

std::vector<RigidTransform> BvhMotion::world_transforms(int frame) const {
  std::vector<RigidTransform> out(joints.size());
  for (size_t j = 0; j < joints.size(); ++j) {
    const RigidTransform local = local_transform(static_cast<int>(j), frame);
    out[j] = joints[j].parent < 0 ? local : out[static_cast<size_t>(joints[j].parent)] * local;
  }
  return out;
}

std::vector<Vec3> BvhMotion::zero_pose_positions() const {
  std::vector<Vec3> out(joints.size());
  for (size_t j = 0; j < joints.size(); ++j)
    out[j] = joints[j].parent < 0 ? joints[j].offset
                                  : out[static_cast<size_t>(joints[j].parent)] + joints[j].offset;
  return out;
}

int BvhMotion::find_joint(const std::string& name) const {
  for (size_t j = 0; j < joints.size(); ++j)
    if (joints[j].name == name) return static_cast<int>(j);
  return -1;
}

BvhMotion parse_bvh(const std::string& text, const std::string& source) {
  return Parser(text, source).parse();
}

BvhMotion import_bvh(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{path.string(), 0, 0, ""}, "cannot open BVH file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_bvh(ss.str(), path.string());
}

}  // namespace crowdlab
