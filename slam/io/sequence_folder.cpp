// A plain folder of images (sorted by name, numbers compared as numbers) at a given rate, and a
// video file decoded with OpenCV.
#include <algorithm>
#include <cctype>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "slam/core/errors.h"
#include "slam/io/sequence.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

bool is_image_file(const fs::path& p);

namespace {

// "img2.png" < "img10.png": digit runs compare by value.
bool natural_less(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      size_t i2 = i, j2 = j;
      while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2]))) ++i2;
      while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2]))) ++j2;
      std::string na = a.substr(i, i2 - i), nb = b.substr(j, j2 - j);
      na.erase(0, std::min(na.find_first_not_of('0'), na.size()));
      nb.erase(0, std::min(nb.find_first_not_of('0'), nb.size()));
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = i2, j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

class ImageFolderReader : public SequenceReader {
 public:
  ImageFolderReader(const fs::path& root, const ReaderOptions& o) {
    if (!(o.rate > 0)) throw InputError(root.string(), "frame rate must be positive");
    info_.kind = DatasetKind::ImageFolder;
    info_.root = root;
    info_.fps = o.rate;
    std::vector<fs::path> images;
    for (const auto& e : fs::directory_iterator(root))
      if (e.is_regular_file() && is_image_file(e.path())) images.push_back(e.path());
    std::sort(images.begin(), images.end(),
              [](const fs::path& a, const fs::path& b) { return natural_less(a.filename().string(), b.filename().string()); });
    for (size_t i = 0; i < images.size(); ++i) {
      Entry e;
      e.timestamp = i / o.rate;
      e.image = images[i];
      entries_.push_back(std::move(e));
    }
    finish_opening();
  }
};

class VideoReader : public SequenceReader {
 public:
  VideoReader(const fs::path& file, const ReaderOptions&) : file_(file) {
    info_.kind = DatasetKind::Video;
    info_.root = file;
    open();
    info_.fps = cap_.get(cv::CAP_PROP_FPS);
    if (!(info_.fps > 0)) info_.fps = 30.0;
    const double n = cap_.get(cv::CAP_PROP_FRAME_COUNT);
    if (!(n > 0)) throw InputError(file.string(), "the video reports no frames");
    for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
      Entry e;
      e.timestamp = i / info_.fps;
      entries_.push_back(e);
    }
    info_.width = static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_WIDTH));
    info_.height = static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_HEIGHT));
    info_.frame_count = entries_.size();
    info_.duration = entries_.size() / info_.fps;
  }

  Frame read_entry(size_t i) override {
    const size_t pos = first_frame_ + i;  // in the video (keep_frames)
    if (pos != next_) {
      cap_.set(cv::CAP_PROP_POS_FRAMES, static_cast<double>(pos));
      next_ = pos;
    }
    Frame f;
    f.index = i;
    f.timestamp = entries_[i].timestamp;
    f.image_path = file_;
    if (!cap_.read(f.image) || f.image.empty())
      throw InputError(file_.string(), "cannot decode frame " + std::to_string(pos));
    ++next_;
    return f;
  }

 private:
  void open() {
    if (!cap_.open(file_.string())) throw InputError(file_.string(), "cannot open the video (unsupported codec or not a video)");
  }
  fs::path file_;
  cv::VideoCapture cap_;
  size_t next_ = 0;
};

}  // namespace

std::unique_ptr<SequenceReader> open_image_folder(const fs::path& root, const ReaderOptions& o) {
  return std::make_unique<ImageFolderReader>(root, o);
}

std::unique_ptr<SequenceReader> open_video(const fs::path& file, const ReaderOptions& o) {
  return std::make_unique<VideoReader>(file, o);
}

}  // namespace wardmap::slam::io
