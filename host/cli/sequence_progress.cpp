#include "cli/sequence_progress.h"

#include <cstdio>
#include <iostream>
#include <utility>

#include "cli/format.h"

namespace phongcl::cli {

namespace {

std::string minutes_seconds(double seconds) {
  const long whole = static_cast<long>(seconds + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld", whole / 60, whole % 60);
  return text;
}

}  // namespace

std::string describe_split(const FrameTimes& t) {
  return "read " + milliseconds(t.read_ms) + ", pack " + milliseconds(t.pack_ms) + ", kernel " + milliseconds(t.kernel_ms) +
         ", download " + milliseconds(t.download_ms) + ", write " + milliseconds(t.write_ms) + ", wait " +
         milliseconds(t.wait_ms);
}

std::string bounding_stage(const FrameTimes& t) {
  const std::pair<double, const char*> stages[] = {{t.read_ms, "read (G-buffer decompression)"},
                                                   {t.pack_ms + t.kernel_ms + t.download_ms, "shading (pack, kernel, download)"},
                                                   {t.write_ms, "write (image compression)"}};
  const auto* longest = &stages[0];
  for (const auto& stage : stages)
    if (stage.first > longest->first) longest = &stage;
  return longest->second;
}

std::string failure_message(const FrameWork& work) {
  try {
    std::rethrow_exception(work.error);
  } catch (const std::exception& error) {
    return "frame " + std::to_string(work.frame) + ": " + error.what();
  } catch (...) {
    return "frame " + std::to_string(work.frame) + ": unknown error";
  }
}

SequenceProgress::SequenceProgress(std::size_t total, bool terminal) : total_(total), terminal_(terminal) {}

void SequenceProgress::frame_done(const FrameWork& work) {
  const std::size_t done_before = shaded_ + failed_.size();
  if (work.error) {
    failed_.push_back(work.frame);
    const std::string message = failure_message(work);
    if (first_failure_.empty()) first_failure_ = message;
    if (terminal_) std::cout << "\r\33[K";
    std::cout << "  failed     " << message << "\n";
  } else {
    ++shaded_;
    totals_ += work.times;
    if (work.report.cache != CacheOutcome::memory_hit) {
      ++builds_;
      build_ms_ += work.report.timings.build_ms;
    }
    if (!terminal_)
      std::cout << "  frame " << work.frame << "  " << describe_split(work.times) << "  [" << done_before + 1 << "/"
                << total_ << "]\n";
  }
  if (terminal_) draw_bar(work.frame);
  std::cout.flush();
}

void SequenceProgress::draw_bar(int frame) {
  constexpr int kWidth = 30;
  const std::size_t done = shaded_ + failed_.size();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fps = seconds > 0 ? static_cast<double>(done) / seconds : 0.0;
  const int filled = total_ > 0 ? static_cast<int>(kWidth * done / total_) : kWidth;
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.2f frames/s", fps);
  std::cout << "\r\33[K  [" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] " << done << "/"
            << total_ << "  " << rate << "  ETA "
            << (fps > 0 ? minutes_seconds(static_cast<double>(total_ - done) / fps) : std::string("?")) << "  frame "
            << frame;
}

void SequenceProgress::finish() {
  if (terminal_) std::cout << "\r\33[K";
  std::cout.flush();
}

}  // namespace phongcl::cli
