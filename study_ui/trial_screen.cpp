#include "study_ui/trial_screen.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "study_ui/session_texts.hpp"

namespace crowdlab::study {
namespace {

const cv::Scalar kBackground(236, 233, 230), kCell(252, 251, 250), kInk(40, 36, 32), kMuted(120, 114, 108);
const cv::Scalar kAccent(196, 112, 28), kGreen(92, 160, 56), kDisabled(196, 192, 188);
const cv::Scalar kBorder(214, 208, 202);

void fill_round_rect(cv::Mat& img, cv::Rect r, int radius, cv::Scalar color) {
  radius = std::min({radius, r.width / 2, r.height / 2});
  cv::rectangle(img, {r.x + radius, r.y, r.width - 2 * radius, r.height}, color, cv::FILLED);
  cv::rectangle(img, {r.x, r.y + radius, r.width, r.height - 2 * radius}, color, cv::FILLED);
  for (cv::Point c :
       {cv::Point(r.x + radius, r.y + radius), cv::Point(r.x + r.width - radius - 1, r.y + radius),
        cv::Point(r.x + radius, r.y + r.height - radius - 1),
        cv::Point(r.x + r.width - radius - 1, r.y + r.height - radius - 1)})
    cv::circle(img, c, radius, color, cv::FILLED, cv::LINE_AA);
}

void draw_centered(cv::Mat& img, const TextRenderer& text, const std::string& s, cv::Rect box, int px,
                   cv::Scalar color) {
  const cv::Size size = text.measure(s, px);
  text.draw(img, s, {box.x + (box.width - size.width) / 2, box.y + (box.height - size.height) / 2}, px,
            color);
}

}  // namespace

int TrialScreenState::first_unanswered(const std::vector<StudyQuestion>& qs, QuestionKind kind) const {
  for (size_t i = 0; i < qs.size() && i < answers.size(); ++i)
    if (qs[i].kind == kind && answers[i] < 0) return static_cast<int>(i);
  return -1;
}

cv::Rect fit_rect(cv::Size frame, cv::Rect area) {
  if (frame.width <= 0 || frame.height <= 0) return area;
  const double s = std::min(static_cast<double>(area.width) / frame.width,
                            static_cast<double>(area.height) / frame.height);
  const int w = std::max(1, static_cast<int>(frame.width * s)),
            h = std::max(1, static_cast<int>(frame.height * s));
  return {area.x + (area.width - w) / 2, area.y + (area.height - h) / 2, w, h};
}

namespace {

/// Sizes of one question cell at scale s (1 = the default, relative to the canvas height H).
struct CellMetrics {
  int body_px, small_px, circle_d, cell_h;
};

CellMetrics cell_metrics(int H, int margin, double s) {
  CellMetrics m;
  m.body_px = std::max(11, static_cast<int>(H * 0.022 * s));
  m.small_px = std::max(10, static_cast<int>(H * 0.017 * s));
  m.circle_d = std::max(16, static_cast<int>(H * 0.034 * s));
  // Two lines of statement, the answer row, one line of end labels, padding above and below.
  m.cell_h = margin + 2 * TextRenderer::line_height(m.body_px) + margin / 4 + m.circle_d +
             TextRenderer::line_height(m.small_px);
  return m;
}

int grid_height(const CellMetrics& m, int rows, int margin) {
  return rows * m.cell_h + (rows - 1) * (margin / 2);
}

/// The answer targets of question i inside its cell.
void place_targets(TrialLayout& L, const StudyQuestion& q, int i, cv::Rect cell, int margin, int circle_d) {
  const int answer_y = cell.y + margin / 2 + 2 * TextRenderer::line_height(L.body_px) + margin / 4;
  if (q.kind == QuestionKind::yesno) {
    const int bw = std::min(cell.width / 3, circle_d * 4);
    const int x0 = cell.x + (cell.width - 2 * bw - circle_d) / 2;
    L.targets.push_back({{x0, answer_y, bw, circle_d}, i, 1});
    L.targets.push_back({{x0 + bw + circle_d, answer_y, bw, circle_d}, i, 0});
    return;
  }
  const int k = q.points;
  const int usable = cell.width - 2 * margin;
  const int step = std::min(usable / k, circle_d * 2);
  const int d = std::min(circle_d, step * 9 / 10);  // 11 points in a narrow cell: smaller circles
  const int x0 = cell.x + (cell.width - step * k) / 2;
  for (int v = 1; v <= k; ++v)
    L.targets.push_back({{x0 + (v - 1) * step + (step - d) / 2, answer_y, d, d}, i, v});
}

}  // namespace

TrialLayout layout_trial_screen(cv::Size canvas, const std::vector<StudyQuestion>& questions,
                                double video_share) {
  TrialLayout L;
  L.canvas = canvas;
  const int W = canvas.width, H = canvas.height;
  const int margin = std::max(6, H / 60);
  const int n = static_cast<int>(questions.size());
  // A compact grid below the video: up to three columns, so six questions take two rows. With two
  // rows the grid fills column by column, so that seed 000's item pairs (Q1/Q2, Q3/Q4, Q5/Q6) share
  // a column; otherwise row by row.
  const int columns = std::max(1, n <= 3 ? n : (n == 4 ? 2 : 3));
  const int rows = (n + columns - 1) / columns;
  const bool column_major = rows == 2 && columns == 3;
  const int next_w = std::max(110, W * 12 / 100);
  const int next_h = std::max(28, H * 55 / 1000);
  const int grid_w = W - 3 * margin - next_w;  // the Next button sits right of the grid
  const int col_w = (grid_w - (columns - 1) * margin) / columns;
  L.header_px = std::max(10, H * 17 / 1000);
  const int header_h = TextRenderer::line_height(L.header_px) + margin / 2;
  const int fixed_h = header_h + margin + margin / 2;  // header, video-grid gap, bottom margin
  // Scale of the question cells: 1 by default (the video takes the rest); with a video share, the
  // largest scale in [0.6, 1.6] whose grid fits beside the requested video height.
  double s = 1.0;
  const int wanted_video_h = static_cast<int>(video_share * H);
  if (video_share > 0.0) {
    s = 1.6;
    while (s > 0.6 && grid_height(cell_metrics(H, margin, s), rows, margin) > H - fixed_h - wanted_video_h)
      s -= 0.05;
  }
  const CellMetrics m = cell_metrics(H, margin, s);
  L.body_px = m.body_px;
  L.small_px = m.small_px;
  const int grid_h = grid_height(m, rows, margin);
  int video_h = std::max(H / 5, H - fixed_h - grid_h);
  if (video_share > 0.0) video_h = std::max(H / 5, std::min(video_h, wanted_video_h));
  L.video_area = {margin, header_h, W - 2 * margin, video_h};
  const int grid_top = H - margin / 2 - grid_h;
  for (int i = 0; i < n; ++i) {
    const int r = column_major ? i % rows : i / columns, c = column_major ? i / rows : i % columns;
    const cv::Rect cell(margin + c * (col_w + margin), grid_top + r * (m.cell_h + margin / 2), col_w,
                        m.cell_h);
    L.cells.push_back(cell);
    place_targets(L, questions[static_cast<size_t>(i)], i, cell, margin, m.circle_d);
  }
  L.next_button = {W - margin - next_w, H - margin / 2 - std::min(next_h, grid_h), next_w,
                   std::min(next_h, grid_h)};
  L.targets.push_back({L.next_button, -1, 0});
  return L;
}

void draw_trial_static(cv::Mat& img, const TrialLayout& L, const std::vector<StudyQuestion>& questions,
                       const std::string& header, bool enabled, const TextRenderer& text) {
  img.setTo(kBackground);
  const int margin = std::max(6, L.canvas.height / 60);
  text.draw(img, header, {margin, margin / 4}, L.header_px, kMuted);
  cv::rectangle(img, L.video_area, cv::Scalar(24, 24, 24), cv::FILLED);
  for (size_t i = 0; i < questions.size(); ++i) {
    const StudyQuestion& q = questions[i];
    const cv::Rect cell = L.cells[i];
    fill_round_rect(img, cell, margin / 2, kCell);
    // Statement: up to two lines, shrinking the font when it does not fit.
    int px = L.body_px;
    std::vector<std::string> lines = text.wrap(q.text, px, cell.width - 2 * margin);
    while (lines.size() > 2 && px > 10) lines = text.wrap(q.text, --px, cell.width - 2 * margin);
    for (size_t l = 0; l < lines.size() && l < 2; ++l)
      text.draw(img, lines[l],
                {cell.x + margin, cell.y + margin / 2 + static_cast<int>(l) * TextRenderer::line_height(px)},
                px, enabled ? kInk : kMuted);
  }
  for (const TrialLayout::Target& t : L.targets) {
    if (t.question < 0) continue;
    const StudyQuestion& q = questions[static_cast<size_t>(t.question)];
    const cv::Scalar ink = enabled ? kInk : kDisabled;
    if (q.kind == QuestionKind::yesno) {
      fill_round_rect(img, t.rect, 3, kCell);
      cv::rectangle(img, t.rect, kBorder, 1, cv::LINE_AA);
      draw_centered(img, text, t.value == 1 ? "Yes (Y)" : "No (N)", t.rect, L.small_px, ink);
      continue;
    }
    const cv::Point c(t.rect.x + t.rect.width / 2, t.rect.y + t.rect.height / 2);
    cv::circle(img, c, t.rect.width / 2, kMuted, 2, cv::LINE_AA);
    draw_centered(img, text, std::to_string(t.value), t.rect, L.small_px, ink);
    const int label_y = t.rect.y + t.rect.height + 2;
    if (t.value == 1 && !q.low_label.empty())
      text.draw(img, q.low_label, {t.rect.x, label_y}, L.small_px * 9 / 10, kMuted);
    if (t.value == q.points && !q.high_label.empty()) {
      const int w = text.measure(q.high_label, L.small_px * 9 / 10).width;
      text.draw(img, q.high_label, {t.rect.x + t.rect.width - w, label_y}, L.small_px * 9 / 10, kMuted);
    }
  }
}

void draw_trial_answers(cv::Mat& img, const TrialLayout& L, const std::vector<StudyQuestion>& questions,
                        const TrialScreenState& state, const TextRenderer& text) {
  const int margin = std::max(6, L.canvas.height / 60);
  const int scale_focus = state.first_unanswered(questions, QuestionKind::scale);
  const int yesno_focus = state.first_unanswered(questions, QuestionKind::yesno);
  for (size_t i = 0; i < questions.size() && state.questions_enabled; ++i)
    if (static_cast<int>(i) == scale_focus || static_cast<int>(i) == yesno_focus)
      cv::rectangle(img, L.cells[i], kAccent, 2, cv::LINE_AA);  // where the keys go
  for (const TrialLayout::Target& t : L.targets) {
    if (t.question < 0 || state.answers[static_cast<size_t>(t.question)] != t.value) continue;
    const StudyQuestion& q = questions[static_cast<size_t>(t.question)];
    if (q.kind == QuestionKind::yesno) {
      fill_round_rect(img, t.rect, 3, kAccent);
      draw_centered(img, text, t.value == 1 ? "Yes (Y)" : "No (N)", t.rect, L.small_px,
                    cv::Scalar(255, 255, 255));
      continue;
    }
    const cv::Point c(t.rect.x + t.rect.width / 2, t.rect.y + t.rect.height / 2);
    cv::circle(img, c, t.rect.width / 2 + 1, kAccent, cv::FILLED, cv::LINE_AA);
    draw_centered(img, text, std::to_string(t.value), t.rect, L.small_px, cv::Scalar(255, 255, 255));
  }
  const bool ready = state.all_answered();
  fill_round_rect(img, L.next_button, margin / 2, ready ? kGreen : kDisabled);
  const char* label = ready                      ? "Next (Enter)"
                      : !state.questions_enabled ? texts::kLockedLabel
                                                 : "Answer every question";
  draw_centered(img, text, label, L.next_button, L.small_px, cv::Scalar(255, 255, 255));
}

void draw_trial_panel(cv::Mat& img, const TrialLayout& L, const std::vector<StudyQuestion>& questions,
                      const TrialScreenState& state, const TextRenderer& text) {
  draw_trial_static(img, L, questions, state.header, state.questions_enabled, text);
  draw_trial_answers(img, L, questions, state, text);
  if (state.confirm_abort) draw_abort_confirmation(img, text);
}

void draw_video_frame(cv::Mat& canvas, const TrialLayout& L, const cv::Mat& frame) {
  if (frame.empty()) return;
  const cv::Rect r = fit_rect(frame.size(), L.video_area);
  cv::Mat roi = canvas(r);
  if (frame.size() == r.size())
    frame.copyTo(roi);
  else
    cv::resize(frame, roi, r.size(), 0, 0, cv::INTER_AREA);
}

std::optional<TrialLayout::Target> hit_test(const TrialLayout& L, const TrialScreenState& state,
                                            cv::Point p) {
  if (state.confirm_abort) return std::nullopt;
  for (const TrialLayout::Target& t : L.targets) {
    if (!t.rect.contains(p)) continue;
    if (t.question < 0 && !state.all_answered()) return std::nullopt;
    if (t.question >= 0 && !state.questions_enabled) return std::nullopt;
    return t;
  }
  return std::nullopt;
}

void draw_text_screen(cv::Mat& img, const std::string& title, const std::string& body,
                      const std::string& hint, const TextRenderer& text) {
  img.setTo(kBackground);
  const int H = img.rows, W = img.cols;
  const int title_px = std::max(16, H * 45 / 1000), body_px = std::max(13, H * 28 / 1000);
  const int width = W * 7 / 10;
  int y = H / 5;
  draw_centered(img, text, title, {0, y, W, TextRenderer::line_height(title_px)}, title_px, kInk);
  y += 2 * TextRenderer::line_height(title_px);
  for (const std::string& line : text.wrap(body, body_px, width)) {
    text.draw(img, line, {(W - width) / 2, y}, body_px, kInk);
    y += TextRenderer::line_height(body_px);
  }
  draw_centered(img, text, hint, {0, H - H / 8, W, TextRenderer::line_height(body_px)}, body_px, kAccent);
}

void draw_inter_trial(cv::Mat& img, const TrialLayout& L, bool fixation) {
  img.setTo(kBackground);
  cv::rectangle(img, L.video_area, cv::Scalar(24, 24, 24), cv::FILLED);
  if (!fixation) return;
  const cv::Point c(L.video_area.x + L.video_area.width / 2, L.video_area.y + L.video_area.height / 2);
  const int arm = std::max(6, L.canvas.height / 40), thickness = std::max(2, L.canvas.height / 300);
  cv::line(img, c - cv::Point(arm, 0), c + cv::Point(arm, 0), cv::Scalar(230, 230, 230), thickness,
           cv::LINE_AA);
  cv::line(img, c - cv::Point(0, arm), c + cv::Point(0, arm), cv::Scalar(230, 230, 230), thickness,
           cv::LINE_AA);
}

void draw_abort_confirmation(cv::Mat& img, const TextRenderer& text) {
  cv::Mat dark;
  img.convertTo(dark, -1, 0.45, 0);
  dark.copyTo(img);
  const int H = img.rows, W = img.cols;
  const cv::Rect box(W / 4, H / 3, W / 2, H / 3);
  fill_round_rect(img, box, H / 60, kCell);
  const int px = std::max(14, H * 32 / 1000);
  draw_centered(img, text, "Quit the session?",
                {box.x, box.y + box.height / 6, box.width, TextRenderer::line_height(px)}, px, kInk);
  const int small = std::max(11, H * 22 / 1000);
  draw_centered(img, text, "Y = quit (your answers so far are saved)",
                {box.x, box.y + box.height / 2, box.width, TextRenderer::line_height(small)}, small, kInk);
  draw_centered(img, text, "any other key = continue",
                {box.x, box.y + box.height / 2 + TextRenderer::line_height(small), box.width,
                 TextRenderer::line_height(small)},
                small, kMuted);
}

}  // namespace crowdlab::study
