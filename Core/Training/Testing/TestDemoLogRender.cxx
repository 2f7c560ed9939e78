// SPDX-License-Identifier: BSD-3-Clause
// The rasteriser against training images (issue 4): the embedded demo log holds a trained
// scene together with its training and test images, so its last snapshot rendered by the
// Core rasteriser must reproduce them about as well as the trainer measured while training.
// The PSNR here is computed independently (8-bit images from the log, a plain loop), and the
// log's own metrics are the reference it is compared with.
#include "Rasterizer.h"
#include "TrainingLogReader.h"

#include "Vis4GSTestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace vis4gs
{
namespace
{
// PSNR of a float render (clamped to [0,1] as evaluation does) against an 8-bit image.
double PsnrAgainst8Bit(const std::vector<float>& render, const std::vector<unsigned char>& image)
{
  double sum = 0;
  for (std::size_t i = 0; i < image.size(); ++i)
  {
    const double r = std::min(1.0, std::max(0.0, static_cast<double>(render[i])));
    const double d = r - image[i] / 255.0;
    sum += d * d;
  }
  return -10.0 * std::log10(sum / static_cast<double>(image.size()));
}
}

TEST(DemoLogRender, LastSnapshotReproducesTrainingImages)
{
  const TrainingLogReader log(testing::SourcePath("Data/Demo/vis4gs-demo.h5"));
  ASSERT_TRUE(log.HasCameras());
  ASSERT_TRUE(log.HasImages());
  const int last = log.GetSnapshotIterations().back();
  SnapshotReadOptions options;
  options.ShDegree = -1;
  const GaussianCloud cloud = log.ReadSnapshot(last, options);
  const std::vector<Camera> cameras = log.ReadCameras();

  double trainSum = 0, testSum = 0;
  int trainViews = 0, testViews = 0;
  double worstTrain = 1e9;
  for (const Camera& camera : cameras)
  {
    ASSERT_EQ(camera.ImagePath.rfind("/images/", 0), 0u) << camera.Name;
    int width = 0, height = 0;
    const auto image = log.ReadImage(camera.ImagePath.substr(8), width, height);
    ASSERT_EQ(width, camera.Width);
    ASSERT_EQ(height, camera.Height);
    const RasterImage<float> render = Rasterize<float>(cloud, camera);
    const double psnr = PsnrAgainst8Bit(render.Color, image);
    EXPECT_TRUE(std::isfinite(psnr)) << camera.Name;
    if (camera.Split == CameraSplit::Train)
    {
      trainSum += psnr;
      worstTrain = std::min(worstTrain, psnr);
      ++trainViews;
    }
    else
    {
      testSum += psnr;
      ++testViews;
    }
  }
  ASSERT_GT(trainViews, 0);
  ASSERT_GT(testViews, 0);
  const double trainPsnr = trainSum / trainViews, testPsnr = testSum / testViews;
  const MetricsTable train = log.ReadMetrics(false), test = log.ReadMetrics(true);
  ASSERT_GT(train.Size(), 0u);
  ASSERT_GT(test.Size(), 0u);
  std::cout << "demo log, iteration " << last << ": rendered PSNR train " << trainPsnr
            << " dB (worst view " << worstTrain << "), test " << testPsnr
            << " dB; the trainer logged train " << train.Psnr.back() << " dB, test "
            << test.Psnr.back() << " dB\n";
  ::testing::Test::RecordProperty("TrainPsnr", std::to_string(trainPsnr));
  ::testing::Test::RecordProperty("TestPsnr", std::to_string(testPsnr));
  // Sanity bounds: a trained scene renders its training views well, every one of them, and
  // generalises less well to the held-out views of the sparse sector.
  EXPECT_GT(trainPsnr, 22.0);
  EXPECT_GT(worstTrain, 15.0);
  EXPECT_LT(testPsnr, trainPsnr);
  // Independent agreement with the trainer's own measurement of the same state: only the
  // 8-bit rounding of the log's images separates the two (measured: 0.004 dB).
  EXPECT_NEAR(trainPsnr, train.Psnr.back(), 0.1);
  EXPECT_NEAR(testPsnr, test.Psnr.back(), 0.1);
}

} // namespace vis4gs
