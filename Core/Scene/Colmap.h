// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Colmap.h
 * @brief The COLMAP sparse model, binary and text (`cameras`, `images`, `points3D`),
 * reference §1.3, and its conversion to Vis4GS cameras.
 *
 * Every standard camera model (ids 0..10) is read with its parameters; distortion
 * parameters are kept (Camera::Distortion) but rendering is pinhole. Parsers work on memory
 * buffers (for fuzzing) and never allocate more than the buffer can hold; errors throw
 * std::runtime_error naming the file, the record and the problem.
 */
#ifndef vis4gs_Colmap_h
#define vis4gs_Colmap_h

#include "Camera.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vis4gs
{

/// One of COLMAP's standard camera models.
struct ColmapCameraModel
{
  int Id;
  const char* Name;
  int NumParams;
  /// True when the model has a single focal length (f, cx, cy, ...).
  bool SingleFocal;
};

/// The model with this id / name, or nullptr.
const ColmapCameraModel* FindColmapModel(int id);
const ColmapCameraModel* FindColmapModel(const std::string& name);

struct ColmapCamera
{
  int Id = 0;
  int ModelId = 1;
  std::uint64_t Width = 0;
  std::uint64_t Height = 0;
  std::vector<double> Params;
};

struct ColmapPoint2D
{
  double X = 0, Y = 0;
  std::int64_t Point3DId = -1; ///< -1: not triangulated
};

struct ColmapImage
{
  int Id = 0;
  std::array<double, 4> Q{ 1, 0, 0, 0 }; ///< world-to-camera rotation, w x y z
  std::array<double, 3> T{ 0, 0, 0 };    ///< world-to-camera translation
  int CameraId = 0;
  std::string Name;                    ///< file name relative to the images folder
  std::vector<ColmapPoint2D> Points2D; ///< empty unless observations were read
};

struct ColmapTrackElement
{
  int ImageId = 0;
  int Point2DIdx = 0;
};

struct ColmapPoint3D
{
  std::uint64_t Id = 0;
  std::array<double, 3> Xyz{ 0, 0, 0 };
  std::array<unsigned char, 3> Rgb{ 0, 0, 0 };
  double Error = 0;
  std::vector<ColmapTrackElement> Track; ///< empty unless observations were read
};

struct ColmapModel
{
  std::vector<ColmapCamera> Cameras;
  std::vector<ColmapImage> Images;
  std::vector<ColmapPoint3D> Points3D;
};

enum class ColmapFormat
{
  Binary,
  Text
};

/// Parsers of one file each; @p name is used in messages. With @p observations false the 2D
/// points of images and the tracks of 3D points are skipped (checked, not stored).
std::vector<ColmapCamera> ParseColmapCameras(const void* data,
  std::size_t size,
  ColmapFormat format,
  const std::string& name);
std::vector<ColmapImage> ParseColmapImages(const void* data,
  std::size_t size,
  ColmapFormat format,
  const std::string& name,
  bool observations = true);
std::vector<ColmapPoint3D> ParseColmapPoints3D(const void* data,
  std::size_t size,
  ColmapFormat format,
  const std::string& name,
  bool observations = true);

/**
 * Reads `<folder>/{cameras,images,points3D}.bin`, or the `.txt` files when there is no
 * cameras.bin (as the trainer does). points3D is optional (an empty list when absent).
 * Checks that every image's camera exists.
 */
ColmapModel ReadColmapModel(const std::string& folder, bool observations = true);

/// Writes the model as `.bin` or `.txt` files into an existing @p folder.
void WriteColmapModel(const std::string& folder, const ColmapModel& model, ColmapFormat format);

/// Pinhole camera of a COLMAP image (fx, fy, cx, cy from the model's parameters, the rest in
/// Distortion; SIMPLE_* models use f for both focals). Name is the image name up to its first
/// '.', as the trainer's image_name; ImagePath is the COLMAP image name.
Camera ToCamera(const ColmapCamera& camera, const ColmapImage& image);

/// True when the model is not a pinhole: a fisheye model, or non-zero distortion parameters.
bool IsDistorted(const ColmapCamera& camera);

} // namespace vis4gs

#endif
