// SPDX-License-Identifier: BSD-3-Clause
// LoadCameraImage: the one way the score filter and the commands read a view's training image,
// from a training log or from a file.
#include "TrainingLogReader.h"

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace vis4gs
{

bool LoadCameraImage(const TrainingLogReader* log,
  const Camera& camera,
  Image& image,
  const std::array<float, 3>& background)
{
  static const std::string prefix = "/images/";
  std::error_code ec;
  const bool onDisk =
    !camera.ImagePath.empty() && std::filesystem::is_regular_file(camera.ImagePath, ec);
  if (log && !onDisk && camera.ImagePath.rfind(prefix, 0) == 0)
  {
    int width = 0, height = 0;
    const std::vector<unsigned char> bytes =
      log->ReadImage(camera.ImagePath.substr(prefix.size()), width, height);
    image =
      PrepareTrainingImage(ImageFromBytes(bytes.data(), width, height, 3), camera, background);
    return true;
  }
  if (!onDisk)
  {
    return false;
  }
  image = LoadTrainingImage(camera, background);
  return true;
}

} // namespace vis4gs
