// wardmap vocabulary train: trains the place-recognition vocabulary (a tree of binary ORB words,
// slam/place/vocabulary.h) on the ORB descriptors of every N-th frame of one or more sequences, and
// writes it atomically.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "apps/commands/commands.h"
#include "apps/common.h"
#include "apps/progress.h"
#include "slam/front/front_options.h"
#include "slam/front/orb_extractor.h"
#include "slam/io/sequence.h"
#include "slam/io/text_file.h"
#include "slam/place/vocabulary_training.h"

namespace wardmap::apps {

namespace {

struct TrainArgs {
  std::vector<std::string> sequences;
  std::string out;
  slam::place::PlaceOptions options;
  int every = 5;
  std::uint32_t seed = 1;
  ReaderArgs reader;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void run_train(const TrainArgs& a) {
  try {
    a.options.validate(slam::place::PlaceOptionNames{"--k", "--levels", "--iterations"});  // this command sets them by flags
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(e.what());
  }
  // Checked before the features and the training, not when the file is written at the end.
  check_output_files({{a.out, "--out"}});
  const auto start = std::chrono::steady_clock::now();
  const slam::OrbExtractor extractor(slam::OrbOptions{});  // the front-process's default ORB settings
  const auto ro = reader_options(a.reader);
  std::vector<cv::Mat> per_image;
  std::size_t descriptors = 0;
  for (const auto& path : a.sequences) {
    auto reader = slam::io::open_sequence(path, ro);
    const std::size_t n = (reader->size() + a.every - 1) / a.every;
    spdlog::info("vocabulary: {} ({} frames, every {}: {} images)", path, reader->size(), a.every, n);
    Progress progress("vocabulary " + std::filesystem::path(path).filename().string(), n, true);
    std::size_t seq_descriptors = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const cv::Mat image = reader->read(k * a.every).image;
      cv::Mat grey = image;
      if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      if (image.channels() == 4) cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
      per_image.push_back(extractor.extract(grey).descriptors);
      seq_descriptors += per_image.back().rows;
      progress.update(k + 1);
    }
    progress.finish();
    descriptors += seq_descriptors;
    spdlog::info("vocabulary: {}: {} descriptors", path, seq_descriptors);
  }
  const double extract_seconds = seconds_since(start);
  spdlog::info("vocabulary: training k = {}, L = {} on {} descriptors of {} images (seed {})", a.options.branching,
               a.options.levels, descriptors, per_image.size(), a.seed);
  const auto train_start = std::chrono::steady_clock::now();
  const slam::place::Vocabulary vocabulary = slam::place::train_vocabulary(per_image, a.options, a.seed);
  const double train_seconds = seconds_since(train_start);
  const std::string bytes = vocabulary.to_bytes();
  slam::io::write_file_atomic(a.out, bytes);
  std::printf(
      "images %zu, descriptors %zu, words %zu (nodes %zu, k %d, L %d), %s: %zu bytes, %.1f s "
      "(features %.1f s, training %.1f s)\n",
      per_image.size(), descriptors, vocabulary.word_count(), vocabulary.node_count(), vocabulary.branching(),
      vocabulary.levels(), a.out.c_str(), bytes.size(), seconds_since(start), extract_seconds, train_seconds);
}

}  // namespace

void add_vocabulary_command(CLI::App& app) {
  CLI::App* voc =
      app.add_subcommand("vocabulary", "Place-recognition vocabulary (binary ORB words) for relocalisation");
  voc->require_subcommand(1);
  auto a = std::make_shared<TrainArgs>();
  CLI::App* cmd = voc->add_subcommand(
      "train",
      "Train a vocabulary tree (hierarchical k-majority on ORB descriptors, tf-idf weights) on every N-th frame of the "
      "sequences and write it to --out");
  cmd->add_option("sequences", a->sequences, "Sequence folders (TUM RGB-D, 7-Scenes, a wardmap synth output, ...)")
      ->required();
  cmd->add_option("--out", a->out, "Vocabulary file to write (written to a temporary name, then renamed)")->required();
  cmd->add_option("--k", a->options.branching, "Branching factor: children per node")->capture_default_str();
  cmd->add_option("--levels", a->options.levels, "Depth of the tree (at most k^levels words)")->capture_default_str();
  cmd->add_option("--iterations", a->options.max_iterations, "k-majority rounds per node")->capture_default_str();
  cmd->add_option("--every", a->every, "Use every N-th frame")->check(whole_number(1))->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed of the k-means++ seeding; the same inputs and seed give the same file")
      ->check(whole_number())
      ->capture_default_str();
  add_reader_options(cmd, a->reader);
  cmd->callback([a]() { run_train(*a); });
}

}  // namespace wardmap::apps
