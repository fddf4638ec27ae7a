// Frame sequences: patterns, frame lists, shards, the three-stage pipeline, and shade's sequence
// mode end to end (same pixels as single-frame runs, resumable, killed and rerun).
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <regex>
#include <sstream>
#include <set>

#include "cli_runner.h"
#include "exr/exr_channels.h"
#include "image/image.h"
#include "opencl_required.h"
#include "sequence/frame_list.h"
#include "sequence/frame_pattern.h"
#include "sequence/frame_pipeline.h"
#include "sequence/shard.h"
#include "temp_dir.h"
#include "wait_until.h"

extern char** environ;

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::run_phongcl;
using testing::TempDir;

TEST(FramePattern, PadsHashesAndPrintfAlike) {
  EXPECT_EQ(FramePattern("lit/shot.####.exr").path(7), "lit/shot.0007.exr");
  EXPECT_EQ(FramePattern("lit/shot.%04d.exr").path(1001), "lit/shot.1001.exr");
  EXPECT_EQ(FramePattern("shot.#.exr").path(12345), "shot.12345.exr");  // padding is a minimum
  EXPECT_EQ(FramePattern("shot.%d.exr").path(42), "shot.42.exr");
  EXPECT_EQ(FramePattern("shot.###.exr").path(-3), "shot.-03.exr");
  EXPECT_FALSE(FramePattern("lit.exr").is_pattern());
  EXPECT_EQ(FramePattern("lit.exr").path(5), "lit.exr");
  EXPECT_TRUE(FramePattern("a.%03d.exr").is_pattern());
}

TEST(FramePattern, RejectsAmbiguousPatterns) {
  EXPECT_THROW(FramePattern("a.####.####.exr"), std::invalid_argument);
  EXPECT_THROW(FramePattern("a.%04d.%d.exr"), std::invalid_argument);
  EXPECT_THROW(FramePattern("a.%s.exr"), std::invalid_argument);
  EXPECT_THROW(FramePattern("a.%012d.exr"), std::invalid_argument);
}

TEST(FramePattern, FindsOnlyFilesItWouldHaveNamed) {
  TempDir dir("sequence");
  for (const char* name : {"g.0001.exr", "g.0010.exr", "g.0002.exr", "g.12345.exr", "g.01.exr", "g.000x.exr",
                           "g.0003.exr.tmp", "h.0004.exr"})
    std::ofstream(dir / name) << "x";
  EXPECT_EQ(FramePattern((dir / "g.####.exr").string()).frames_on_disk(), (std::vector<int>{1, 2, 10, 12345}));
  EXPECT_EQ(FramePattern((dir / "g.%d.exr").string()).frames_on_disk(), (std::vector<int>{12345}));
}

TEST(FrameList, RangesStepsAndLists) {
  EXPECT_EQ(parse_frame_list("1001-1004"), (std::vector<int>{1001, 1002, 1003, 1004}));
  EXPECT_EQ(parse_frame_list("1-10x3"), (std::vector<int>{1, 4, 7, 10}));
  EXPECT_EQ(parse_frame_list("5,1-3,2"), (std::vector<int>{1, 2, 3, 5}));
  EXPECT_EQ(parse_frame_list("7"), (std::vector<int>{7}));
  EXPECT_EQ(parse_frame_list("-2-1"), (std::vector<int>{-2, -1, 0, 1}));
}

TEST(FrameList, BadItemsAreNamed) {
  for (const char* bad : {"", "10-5", "a", "1-5x0", "1,,2", "1-", "1-2-3", "1-1000000000"}) {
    try {
      parse_frame_list(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("--frames"), std::string::npos) << error.what();
    }
  }
}

TEST(Shard, EveryFrameExactlyOnceAcrossShards) {
  const std::vector<int> frames = parse_frame_list("1001-1010,1020");
  for (int count : {1, 3, 4, 11, 16}) {
    std::multiset<int> all;
    for (int index = 0; index < count; ++index) {
      const std::vector<int> mine = frames_of_shard(frames, {index, count});
      all.insert(mine.begin(), mine.end());
    }
    EXPECT_EQ(std::vector<int>(all.begin(), all.end()), frames) << count << " shards";
  }
  EXPECT_EQ(frames_of_shard(frames, parse_shard("1/4")), (std::vector<int>{1002, 1006, 1010}));
  for (const char* bad : {"4/4", "1/0", "x", "1/", "-1/4"}) EXPECT_THROW(parse_shard(bad), std::invalid_argument) << bad;
}

TEST(Shard, FromASlurmJobArray) {
  std::map<std::string, std::string> env;
  auto getenv = [&](const char* name) -> const char* {
    const auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  };
  EXPECT_FALSE(shard_from_slurm(getenv).has_value());
  env = {{"SLURM_ARRAY_TASK_ID", "6"}, {"SLURM_ARRAY_TASK_MIN", "4"}, {"SLURM_ARRAY_TASK_MAX", "7"},
         {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_STEP", "1"}};
  const std::optional<Shard> shard = shard_from_slurm(getenv);
  ASSERT_TRUE(shard.has_value());
  EXPECT_EQ(shard->index, 2);
  EXPECT_EQ(shard->count, 4);
  env = {{"SLURM_ARRAY_TASK_ID", "4"}, {"SLURM_ARRAY_TASK_MIN", "0"}, {"SLURM_ARRAY_TASK_MAX", "6"},
         {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_STEP", "2"}};  // --array=0-6:2
  EXPECT_EQ(shard_from_slurm(getenv)->index, 2);
  env = {{"SLURM_ARRAY_TASK_ID", "4"}, {"SLURM_ARRAY_TASK_MIN", "1"}, {"SLURM_ARRAY_TASK_MAX", "9"},
         {"SLURM_ARRAY_TASK_COUNT", "3"}};  // --array=1,4,9
  EXPECT_THROW(shard_from_slurm(getenv), std::invalid_argument);
}

// Stages that record the frames they see and how many of them run at once. With `meet` set, the three
// stage runs a pipeline can overlap first (write frame 1, shade frame 2, read frame 3) each wait until
// all three are running: they meet only where the stages do overlap, and a pipeline that ran them one
// after another leaves them waiting until the deadline.
struct RecordingStages {
  bool meet = false;
  std::mutex mutex;
  std::condition_variable arrived;
  int busy = 0, most_busy = 0, met = 0;
  std::vector<int> read_frames;
  std::set<int> failing_reads;

  void enter(bool meeting) {
    std::unique_lock lock(mutex);
    most_busy = std::max(most_busy, ++busy);
    if (meet && meeting) {
      ++met;
      arrived.notify_all();
      arrived.wait_for(lock, std::chrono::seconds(10), [&] { return met == 3; });
    }
    --busy;
  }
  FrameStages stages() {
    return {[this](FrameWork& work) {
              {
                std::lock_guard lock(mutex);
                read_frames.push_back(work.frame);
              }
              enter(work.frame == 3);
              if (failing_reads.count(work.frame)) throw std::runtime_error("unreadable");
            },
            [this](FrameWork& work) {
              enter(work.frame == 2);
              work.image = Image(1, 1);
              work.image.rgba[0] = static_cast<float>(work.frame);
            },
            [this](FrameWork& work) {
              enter(work.frame == 1);
              work.written = std::to_string(work.image.rgba[0]);
            }};
  }
};

TEST(FramePipeline, OverlapsTheStagesAndKeepsFrameOrder) {
  RecordingStages recording;
  recording.meet = true;
  std::vector<int> done;
  run_frame_pipeline({1, 2, 3, 4, 5, 6}, recording.stages(), {}, [&](const FrameWork& work) {
    EXPECT_FALSE(work.error);
    EXPECT_EQ(work.written, std::to_string(static_cast<float>(work.frame)));  // every stage saw this frame
    done.push_back(work.frame);
  });
  EXPECT_EQ(done, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(recording.most_busy, 3) << "read, shade and write never ran at the same time";
}

TEST(FramePipeline, AFailedFrameStopsReadingUnlessKeepGoing) {
  for (const bool keep_going : {false, true}) {
    RecordingStages recording;
    recording.failing_reads = {2};
    std::vector<int> done, failed;
    run_frame_pipeline({1, 2, 3, 4, 5, 6, 7, 8}, recording.stages(), {nullptr, keep_going}, [&](const FrameWork& work) {
      (work.error ? failed : done).push_back(work.frame);
      if (work.error) {
        EXPECT_TRUE(work.written.empty()) << "a failed frame was written";
      }
    });
    EXPECT_EQ(failed, (std::vector<int>{2}));
    if (keep_going) {
      EXPECT_EQ(done, (std::vector<int>{1, 3, 4, 5, 6, 7, 8}));
    } else {
      EXPECT_EQ(done, std::vector<int>{1}) << "frames after a failure were shaded";
      EXPECT_LE(recording.read_frames.size(), 3u) << "reading went on after the failure";
    }
  }
}

TEST(FramePipeline, AStopFinishesWhatIsInFlight) {
  RecordingStages recording;
  std::atomic<bool> stop{false};
  std::vector<int> done;
  run_frame_pipeline({1, 2, 3, 4, 5, 6, 7, 8}, recording.stages(), {&stop, false}, [&](const FrameWork& work) {
    EXPECT_FALSE(work.error);
    done.push_back(work.frame);
    stop = true;
  });
  EXPECT_GE(done.size(), 1u);
  // In flight when the first frame is done: one frame in each stage and in each of the two queues.
  EXPECT_LE(done.size(), 5u) << "a stop should end reading within the frames in flight";
  EXPECT_EQ(done.size(), recording.read_frames.size()) << "a frame read was neither finished nor reported";
}

// shade's sequence mode end to end, on copies of the bundled 640x480 G-buffer with a light that
// moves from frame to frame (one scene file per frame).
class ShadeSequence : public ::testing::Test {
 protected:
  void SetUp() override {
    PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
    const std::string scene = testing::read_text(PHONGCL_SOURCE_DIR "/scenes/default/scene.json");
    for (int frame = 1; frame <= kFrames; ++frame) {
      fs::copy_file(PHONGCL_SOURCE_DIR "/scenes/default/gbuffer.exr", dir_ / name("g", frame, ".exr"));
      std::string moved = scene;
      const std::size_t light = moved.find("[4, 6, 5]");
      ASSERT_NE(light, std::string::npos) << "the bundled scene's first light moved";
      moved.replace(light, 9, "[" + std::to_string(frame) + ", 6, 5]");
      std::ofstream(dir_ / name("s", frame, ".json")) << moved;
    }
  }

  static constexpr int kFrames = 8;
  static std::string name(const char* prefix, int frame, const char* extension) {
    char text[64];
    std::snprintf(text, sizeof text, "%s.%04d%s", prefix, frame, extension);
    return text;
  }
  std::string sequence_arguments() const {
    return "shade --scene " + (dir_ / "s.####.json").string() + " --gbuffer " + (dir_ / "g.%04d.exr").string() +
           " --out " + (dir_ / "lit.####.exr").string();
  }
  // Frame `frame` shaded by a single-frame run.
  Image single_frame(int frame) const {
    const fs::path out = dir_ / ("single" + std::to_string(frame) + ".exr");
    const testing::CliRun run = run_phongcl("shade --scene " + (dir_ / name("s", frame, ".json")).string() + " --gbuffer " +
                                            (dir_ / name("g", frame, ".exr")).string() + " --out " + out.string());
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return read_exr(out);
  }
  // The frames a run printed a line for ("  frame 3  read ...").
  static std::vector<int> frames_shaded(const std::string& out) {
    std::vector<int> frames;
    static const std::regex line(R"(\n  frame (\d+)  read)");
    for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator(); ++it)
      frames.push_back(std::stoi((*it)[1].str()));
    return frames;
  }
  int outputs_written() const {
    int found = 0;
    for (int frame = 1; frame <= kFrames; ++frame) found += fs::exists(dir_ / name("lit", frame, ".exr"));
    return found;
  }
  std::vector<fs::path> temporaries() const {
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(dir_.path))
      if (entry.path().filename().string().find(".tmp") != std::string::npos) found.push_back(entry.path());
    return found;
  }
  void expect_matches_single_frame(int frame) const {
    const Image sequence = read_exr(dir_ / name("lit", frame, ".exr"));
    const Image single = single_frame(frame);
    // The same kernel on the same inputs: bit for bit, not within a tolerance.
    EXPECT_TRUE(sequence.rgba == single.rgba) << "frame " << frame << " differs from a single-frame run";
  }

  TempDir dir_{"shade_sequence"};
};

TEST_F(ShadeSequence, ShadesEveryFrameLikeSingleFrameRuns) {
  const testing::CliRun run = run_phongcl(sequence_arguments() + " --frames 1-8x3 --threads 2");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_EQ(frames_shaded(run.out), (std::vector<int>{1, 4, 7})) << run.out;
  for (const char* expected : {"3 frames (1-7)", "3 shaded, 0 failed, 0 skipped", "builds     1 program build", "bound by"})
    EXPECT_NE(run.out.find(expected), std::string::npos) << expected << " in\n" << run.out;
  for (int frame : {1, 4, 7}) expect_matches_single_frame(frame);
  EXPECT_FALSE(fs::exists(dir_ / name("lit", 2, ".exr")));
  EXPECT_NE(read_exr(dir_ / name("lit", 1, ".exr")).rgba, read_exr(dir_ / name("lit", 7, ".exr")).rgba)
      << "the moving light did not move";
}

TEST_F(ShadeSequence, OutputsKeepTheInputsCompressionUnlessAsked) {
  const std::string single = "shade --scene " + (dir_ / name("s", 1, ".json")).string() + " --gbuffer " +
                             (dir_ / name("g", 1, ".exr")).string() + " --threads 1 --out ";
  ASSERT_EQ(run_phongcl(single + (dir_ / "zip.exr").string()).exit_code, 0);
  const testing::CliRun piz = run_phongcl(single + (dir_ / "piz.exr").string() + " --compression piz");
  ASSERT_EQ(piz.exit_code, 0) << piz.err;
  EXPECT_NE(piz.out.find("(piz)"), std::string::npos) << piz.out;
  for (const char* expected : {"time       read ", ", write ", " wall clock"})
    EXPECT_NE(piz.out.find(expected), std::string::npos) << expected << " in\n" << piz.out;
  EXPECT_EQ(exr::InputExr(dir_ / name("g", 1, ".exr")).compression(), ExrCompression::zip);
  EXPECT_EQ(exr::InputExr(dir_ / "zip.exr").compression(), ExrCompression::zip);
  EXPECT_EQ(exr::InputExr(dir_ / "piz.exr").compression(), ExrCompression::piz);
  EXPECT_TRUE(read_exr(dir_ / "piz.exr").rgba == read_exr(dir_ / "zip.exr").rgba) << "PIZ and ZIP are lossless";
  // A PIZ G-buffer gives PIZ outputs.
  ASSERT_EQ(run_phongcl("shade --scene " + (dir_ / name("s", 1, ".json")).string() + " --gbuffer " +
                        (dir_ / "piz.exr").string() + " --out " + (dir_ / "from_piz.exr").string() + " --layout aov "
                        "--channel position=R,G,B --channel normal=R,G,B")
                .exit_code,
            0);
  EXPECT_EQ(exr::InputExr(dir_ / "from_piz.exr").compression(), ExrCompression::piz);
}

TEST_F(ShadeSequence, ExistingOutputsAreDoneUnlessOverwrite) {
  ASSERT_EQ(run_phongcl(sequence_arguments() + " --frames 1-3").exit_code, 0);
  const auto written = fs::last_write_time(dir_ / name("lit", 2, ".exr"));
  fs::remove(dir_ / name("lit", 3, ".exr"));
  const testing::CliRun rerun = run_phongcl(sequence_arguments() + " --frames 1-3");
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_EQ(frames_shaded(rerun.out), std::vector<int>{3}) << rerun.out;
  EXPECT_NE(rerun.out.find("skipped    2 frames whose outputs exist"), std::string::npos) << rerun.out;
  EXPECT_EQ(fs::last_write_time(dir_ / name("lit", 2, ".exr")), written);
  const testing::CliRun overwrite = run_phongcl(sequence_arguments() + " --frames 1-3 --overwrite");
  EXPECT_EQ(frames_shaded(overwrite.out), (std::vector<int>{1, 2, 3})) << overwrite.out;
}

TEST_F(ShadeSequence, FramesOnDiskAndShards) {
  // No --frames: the G-buffer frames found; shards 0/3..2/3 together make each frame once.
  for (int index = 0; index < 3; ++index) {
    const testing::CliRun run = run_phongcl(sequence_arguments() + " --shard " + std::to_string(index) + "/3");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("8 frames (1-8)"), std::string::npos) << run.out;
    std::vector<int> expected;
    for (int frame = 1 + index; frame <= kFrames; frame += 3) expected.push_back(frame);
    EXPECT_EQ(frames_shaded(run.out), expected) << run.out;
  }
  // A Slurm array task picks its shard from the environment and says so.
  fs::remove(dir_ / name("lit", 2, ".exr"));
  const testing::CliRun slurm = run_phongcl(sequence_arguments(),
                                            "SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=2 "
                                            "SLURM_ARRAY_TASK_COUNT=3 SLURM_ARRAY_TASK_STEP=1 ");
  ASSERT_EQ(slurm.exit_code, 0) << slurm.err;
  EXPECT_NE(slurm.out.find("shard      1/3 (Slurm job array task 1)"), std::string::npos) << slurm.out;
  EXPECT_EQ(frames_shaded(slurm.out), std::vector<int>{2}) << slurm.out;
}

TEST_F(ShadeSequence, AMissingFrameIsNamedAndKeepGoingShadesTheRest) {
  fs::remove(dir_ / name("g", 2, ".exr"));
  const testing::CliRun stop = run_phongcl(sequence_arguments() + " --frames 1-4");
  EXPECT_NE(stop.exit_code, 0);
  EXPECT_NE(stop.err.find("frame 2: "), std::string::npos) << stop.err;
  EXPECT_NE(stop.err.find("g.0002.exr: no such file"), std::string::npos) << stop.err;
  EXPECT_EQ(std::count(stop.err.begin(), stop.err.end(), '\n'), 1) << stop.err;
  EXPECT_FALSE(fs::exists(dir_ / name("lit", 4, ".exr"))) << "shading went on after a failed frame";

  const testing::CliRun going = run_phongcl(sequence_arguments() + " --frames 1-4 --keep-going");
  EXPECT_NE(going.exit_code, 0);
  EXPECT_NE(going.err.find("1 frames failed: 2"), std::string::npos) << going.err;
  for (int frame : {1, 3, 4}) EXPECT_TRUE(fs::exists(dir_ / name("lit", frame, ".exr"))) << frame;
  EXPECT_TRUE(temporaries().empty());
}

TEST_F(ShadeSequence, BadSequencesAreOneLineErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {" --frames 1-3 --compression lzw", "--compression"},
      {" --frames 5-1", "ends before it starts"},
      {" --shard 3/3", "--shard '3/3'"},
  };
  for (const auto& [extra, message] : cases) {
    const testing::CliRun run = run_phongcl(sequence_arguments() + extra);
    EXPECT_NE(run.exit_code, 0) << extra;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
  const testing::CliRun one_file = run_phongcl("shade --scene " + (dir_ / name("s", 1, ".json")).string() + " --gbuffer " +
                                               (dir_ / "g.####.exr").string() + " --out " + (dir_ / "lit.exr").string());
  EXPECT_NE(one_file.err.find("names one file for every frame"), std::string::npos) << one_file.err;
}

// Starts phongcl with stdout to a file and returns its pid.
pid_t spawn_phongcl(const std::string& arguments, const fs::path& log) {
  std::vector<std::string> words{PHONGCL_EXE};
  std::istringstream split(arguments);
  for (std::string word; split >> word;) words.push_back(word);
  std::vector<char*> argv;
  for (auto& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, (log.string() + ".err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, PHONGCL_EXE, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// Waits until `count` outputs exist, then sends `signal`; returns the wait status, or nothing for a
// run that still went on a minute later (it is then killed).
std::optional<int> interrupt_after(pid_t pid, const std::function<int()>& outputs, int count, int signal) {
  testing::wait_until([&] { return outputs() >= count; }, std::chrono::seconds(120));
  ::kill(pid, signal);
  return testing::wait_for_child(pid);
}

TEST_F(ShadeSequence, KilledMidSequenceAndRerunShadesEachFrameOnce) {
  auto outputs = [&] { return outputs_written(); };
  const std::optional<int> status =
      interrupt_after(spawn_phongcl(sequence_arguments(), dir_ / "killed.log"), outputs, 2, SIGKILL);
  ASSERT_TRUE(status && WIFSIGNALED(*status)) << "the run ended before it could be killed";
  std::map<int, fs::file_time_type> survivors;
  for (int frame = 1; frame <= kFrames; ++frame)
    if (fs::exists(dir_ / name("lit", frame, ".exr")))
      survivors[frame] = fs::last_write_time(dir_ / name("lit", frame, ".exr"));
  ASSERT_LT(survivors.size(), static_cast<std::size_t>(kFrames)) << "every frame was done before the kill";

  const testing::CliRun rerun = run_phongcl(sequence_arguments());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.out << rerun.err;
  std::vector<int> missing;
  for (int frame = 1; frame <= kFrames; ++frame)
    if (!survivors.count(frame)) missing.push_back(frame);
  EXPECT_EQ(frames_shaded(rerun.out), missing) << "the rerun must shade exactly the frames the kill left undone\n"
                                               << rerun.out;
  for (const auto& [frame, time] : survivors)
    EXPECT_EQ(fs::last_write_time(dir_ / name("lit", frame, ".exr")), time) << "frame " << frame << " shaded twice";
  for (int frame = 1; frame <= kFrames; ++frame) expect_matches_single_frame(frame);
  EXPECT_TRUE(temporaries().empty()) << "the kill left a temporary: " << temporaries().front();
}

TEST_F(ShadeSequence, InterruptFinishesTheFramesInFlight) {
  auto outputs = [&] { return outputs_written(); };
  const std::optional<int> status =
      interrupt_after(spawn_phongcl(sequence_arguments(), dir_ / "interrupted.log"), outputs, 1, SIGINT);
  ASSERT_TRUE(status) << "the run went on for a minute after SIGINT";
  ASSERT_TRUE(WIFEXITED(*status)) << "SIGINT killed the run instead of stopping it";
  const int written = outputs_written();
  if (written == kFrames) GTEST_SKIP() << "the run finished before the interrupt arrived";
  EXPECT_EQ(WEXITSTATUS(*status), 1);
  EXPECT_NE(testing::read_text(dir_ / "interrupted.log.err").find("stopped by signal 2"), std::string::npos);
  EXPECT_TRUE(temporaries().empty()) << "an in-flight frame left a temporary: " << temporaries().front();
  for (int frame = 1; frame <= kFrames; ++frame)
    if (fs::exists(dir_ / name("lit", frame, ".exr"))) expect_matches_single_frame(frame);
}

}  // namespace
}  // namespace phongcl
