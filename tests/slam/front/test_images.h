// Shared helpers of the front-end tests: a deterministic textured image.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace wardmap::test {

// Random filled rectangles and circles of random grey levels on a noisy background (fixed seed).
inline cv::Mat textured_image(int width = 640, int height = 480, unsigned seed = 7) {
  cv::RNG rng(seed);
  cv::Mat img(height, width, CV_8UC1);
  rng.fill(img, cv::RNG::UNIFORM, 90, 160);
  cv::GaussianBlur(img, img, cv::Size(5, 5), 1.5);
  for (int i = 0; i < 900; ++i) {
    const cv::Point p(rng.uniform(0, width), rng.uniform(0, height));
    const int s = rng.uniform(3, 22);
    const int g = rng.uniform(0, 256);
    if (i % 2)
      cv::rectangle(img, p, p + cv::Point(s, rng.uniform(3, 22)), cv::Scalar(g), cv::FILLED);
    else
      cv::circle(img, p, s / 2 + 1, cv::Scalar(g), cv::FILLED);
  }
  return img;
}

}  // namespace wardmap::test
