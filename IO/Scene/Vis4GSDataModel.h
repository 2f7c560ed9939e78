/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSDataModel.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @file Vis4GSDataModel.h
 * @brief Conversion between Core's Gaussian scene and cameras and their VTK form (DESIGN §2).
 *
 * The array names below are the contract between modules. A Gaussian scene is a vtkPolyData
 * whose points are the means; cameras are a vtkTable with one row per view. Every reader,
 * writer and filter converts through these functions so the names and layouts live in one
 * place.
 */
#ifndef Vis4GSDataModel_h
#define Vis4GSDataModel_h

#include "vis4gsIOSceneModule.h" // For export macro

#include "Camera.h"        // For vis4gs::Camera
#include "GaussianCloud.h" // For vis4gs::GaussianCloud

#include "vtkAbstractArray.h" // For VTK_DATA_ARRAY_USER_DEFINED
#include "vtkSmartPointer.h"  // For vtkSmartPointer

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

class vtkDataArray;
class vtkPolyData;
class vtkTable;

namespace vis4gs
{
namespace arrays
{
// Gaussian point data
constexpr const char* GaussianId = "GaussianId";
constexpr const char* LogScale = "LogScale";
constexpr const char* Rotation = "Rotation";
constexpr const char* OpacityLogit = "OpacityLogit";
constexpr const char* SH = "SH";
constexpr const char* Opacity = "Opacity";
constexpr const char* Scale = "Scale";
constexpr const char* ViewCoverage = "ViewCoverage";
constexpr const char* BlurScore = "BlurScore";
constexpr const char* NeedleScore = "NeedleScore";
constexpr const char* NeedleShape = "NeedleShape";
/// 1 where no training view sees the Gaussian (vtkGaussianArtifactScoreFilter).
constexpr const char* NoVisibleView = "NoVisibleView";
// Gaussian field data
constexpr const char* SHDegree = "SHDegree";
// Metrics table columns: one spelling everywhere (the training-log reader's metrics port, the
// application's tables, the timeline view's defaults); test-set columns of the reader's
// merged table carry the prefix MetricTestPrefix ("TestPSNR").
constexpr const char* MetricIteration = "Iteration";
constexpr const char* MetricGaussians = "NumGaussians";
constexpr const char* MetricLoss = "Loss";
constexpr const char* MetricL1 = "L1";
constexpr const char* MetricPSNR = "PSNR";
constexpr const char* MetricSSIM = "SSIM";
constexpr const char* MetricLPIPS = "LPIPS";
constexpr const char* MetricElapsed = "ElapsedSeconds";
constexpr const char* MetricTestPrefix = "Test";
// Camera table columns
constexpr const char* CameraName = "Name";
constexpr const char* CameraSplit = "Split";
constexpr const char* CameraWidth = "Width";
constexpr const char* CameraHeight = "Height";
constexpr const char* CameraFx = "Fx";
constexpr const char* CameraFy = "Fy";
constexpr const char* CameraCx = "Cx";
constexpr const char* CameraCy = "Cy";
constexpr const char* CameraWorldToCamera = "WorldToCamera";
constexpr const char* CameraImage = "Image";
constexpr const char* CameraModel = "Model";
constexpr const char* CameraDistortion = "Distortion";
/// Camera table field data: the training log holding the "/images/<name>" images.
constexpr const char* CameraTrainingLogFile = "TrainingLogFile";
// Events table columns (DESIGN §3 /events; Kind values are vis4gs::EventKind) and the field
// data the genealogy filter reads from it.
constexpr const char* EventIteration = "Iteration";
constexpr const char* EventKind = "Kind";
constexpr const char* EventParent = "Parent";
constexpr const char* EventChild = "Child";
constexpr const char* EventInitialIds = "InitialIds";
constexpr const char* EventInitialCount = "NumberOfInitialGaussians";
constexpr const char* EventLastIteration = "LastIteration";
// The log's /lineage_breaks as field data of the events table, one tuple per break
// (vis4gs::LineageBreakTable's columns; present only when the log has breaks).
constexpr const char* EventBreakIteration = "LineageBreakIteration";
constexpr const char* EventBreakEventRow = "LineageBreakEventRow";
constexpr const char* EventBreakTracked = "LineageBreakTracked";
constexpr const char* EventBreakRows = "LineageBreakRows";
constexpr const char* EventBreakKept = "LineageBreakKept";
constexpr const char* EventBreakFirstNewId = "LineageBreakFirstNewId";
constexpr const char* EventBreakNewRoots = "LineageBreakNewRoots";
// Property history (long format, one row per Gaussian and snapshot): the table
// vtkGaussianTrainingLogReader::GetPropertyHistory gives the application and a script alike
// and the timeline view draws (GaussianId, Iteration, Position, LogScale, Rotation,
// OpacityLogit, SHDC, Opacity, Scale; a vector drawn by one component or its largest).
constexpr const char* HistoryIteration = "Iteration";
constexpr const char* HistoryPosition = "Position";
constexpr const char* HistorySHDC = "SHDC";
// Genealogy tree (vtkGaussianGenealogyTreeFilter) vertex data read by the views
constexpr const char* TreeGaussianId = "GaussianId";
constexpr const char* TreeLayoutX = "LayoutX";
constexpr const char* TreeLayoutY = "LayoutY";
constexpr const char* TreeFamilyId = "FamilyId";
/// u8, 1 for a root started by a lineage break (present only when the log has breaks).
constexpr const char* TreeLineageBreakRoot = "LineageBreakRoot";
// Before / after of a clean-up (vtkGaussianRemovalEffectFilter): the columns of
// `vis4gs analyze --report`'s before-after.csv, spelled as there. Per view: RemovalView,
// RemovalCamera (index in the camera table), RemovalSplit ("train" / "test"), RemovalAffected
// (1 where a removed Gaussian took part), then the figures; per split (totals): RemovalSplit,
// RemovalViews (views with an image), RemovalAffected (views changed), then the figures (means).
constexpr const char* RemovalView = "view";
constexpr const char* RemovalCamera = "camera";
constexpr const char* RemovalSplit = "split";
constexpr const char* RemovalAffected = "affected";
constexpr const char* RemovalViews = "views";
constexpr const char* RemovalPsnrBefore = "psnr_before";
constexpr const char* RemovalPsnrAfter = "psnr_after";
constexpr const char* RemovalSsimBefore = "ssim_before";
constexpr const char* RemovalSsimAfter = "ssim_after";
constexpr const char* RemovalL1Before = "l1_before";
constexpr const char* RemovalL1After = "l1_after";
}

namespace detail
{
/// Registers @p owner to live until VTK frees @p data; returns the free function to give VTK.
VIS4GSIOSCENE_EXPORT void (*AdoptBuffer(void* data, std::shared_ptr<void> owner))(void*);
}

/**
 * A VTK array named @p name that takes over the memory of @p values (no copy): VTK frees it
 * with the array. How the readers hand Core's large vectors to VTK without holding two copies.
 */
template <typename ArrayT, typename T>
vtkSmartPointer<ArrayT> AdoptVector(const char* name, std::vector<T>&& values, int components = 1)
{
  using V = typename ArrayT::ValueType;
  static_assert(sizeof(V) == sizeof(T) &&
      std::is_integral<V>::value == std::is_integral<T>::value &&
      std::is_signed<V>::value == std::is_signed<T>::value,
    "the array's value type must have the vector's representation");
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  if (values.empty())
  {
    return array;
  }
  auto owner = std::make_shared<std::vector<T>>(std::move(values));
  V* data = reinterpret_cast<V*>(owner->data());
  array->SetArray(
    data, static_cast<vtkIdType>(owner->size()), 0, vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(detail::AdoptBuffer(data, std::move(owner)));
  return array;
}

/// What GaussianCloudToPolyData adds besides the raw parameters.
struct PolyDataOptions
{
  /// Add the activated Opacity and Scale arrays (for display and tables).
  bool ActivatedArrays = true;
};

/**
 * Fills @p output with the Gaussians of @p cloud: points = means (float), raw parameter arrays
 * (those loaded in @p cloud; empty vectors are left out), GaussianId as pedigree ids, extra
 * properties as arrays of their own type, SHDegree as field data. Float values are copied
 * bit-exactly.
 */
VIS4GSIOSCENE_EXPORT void GaussianCloudToPolyData(const GaussianCloud& cloud,
  vtkPolyData* output,
  const PolyDataOptions& options = {});

/**
 * The same, taking over @p cloud without copying: the cloud moves into shared storage whose
 * vectors the arrays of @p output are (points, LogScale, Rotation, OpacityLogit, SH and
 * GaussianId; GaussianId is filled with 0..n-1 when @p cloud has no ids), so that
 * SharedGaussianCloud can give the Core form back without a second copy. The storage lives
 * while any of those arrays or a holder of the shared cloud does. Extra properties are copied
 * into arrays of their own and not kept in the shared cloud.
 */
VIS4GSIOSCENE_EXPORT void GaussianCloudToPolyData(GaussianCloud&& cloud,
  vtkPolyData* output,
  const PolyDataOptions& options = {});

/**
 * The Core cloud whose vectors the parameter arrays of @p input are (made by
 * GaussianCloudToPolyData(GaussianCloud&&), passed on by shallow copies), or null when any of
 * those arrays is not that cloud's (replaced, reallocated, converted, removed). When not null
 * it equals what PolyDataToGaussianCloud(input, cloud, error, false) gives, without a copy:
 * the arrays and the cloud are one memory, so a value written into an array is the cloud's.
 */
VIS4GSIOSCENE_EXPORT std::shared_ptr<const GaussianCloud> SharedGaussianCloud(vtkPolyData* input);

/**
 * The Core form of @p input for reading: SharedGaussianCloud when the arrays are one, else a
 * new cloud converted by PolyDataToGaussianCloud (null, with a message in @p error, when the
 * input is not a Gaussian scene).
 */
VIS4GSIOSCENE_EXPORT std::shared_ptr<const GaussianCloud> GaussianCloudOf(vtkPolyData* input,
  std::string* error);

/**
 * Reads a Gaussian scene back from @p input. Missing parameter arrays stay empty in @p cloud;
 * arrays that are present with the wrong number of components, or a missing point set, give
 * false and a message in @p error. Point-data arrays that are not part of the model (scores,
 * normals, other tools' properties) are returned as extra properties when @p withExtras.
 */
VIS4GSIOSCENE_EXPORT bool PolyDataToGaussianCloud(vtkPolyData* input,
  GaussianCloud& cloud,
  std::string* error,
  bool withExtras = false);

/**
 * The point-data arrays of @p input that are not part of the model (scores, normals, other
 * tools' properties), one property per component, as PolyDataToGaussianCloud's extras: for a
 * caller that reads the parameters through SharedGaussianCloud without a copy and still keeps
 * a file's other properties.
 */
VIS4GSIOSCENE_EXPORT std::vector<ExtraProperty> PolyDataExtraProperties(vtkPolyData* input);

/// Fills @p table with one row per camera (columns named in vis4gs::arrays).
VIS4GSIOSCENE_EXPORT void CamerasToTable(const std::vector<Camera>& cameras, vtkTable* table);

/// Reads cameras back from @p table; false with a message in @p error when a column is missing.
VIS4GSIOSCENE_EXPORT bool TableToCameras(vtkTable* table,
  std::vector<Camera>& cameras,
  std::string* error);

/// The first row of @p table that is a training camera (Split 0): the view a user knows the
/// scene from, where a window starts (a test camera may come first); 0 when none is, -1 for no
/// table or no row.
VIS4GSIOSCENE_EXPORT vtkIdType FirstTrainingCamera(vtkTable* table);

/// A new VTK array holding a copy of @p extra (vtkFloatArray for Float32, and so on).
VIS4GSIOSCENE_EXPORT vtkDataArray* NewArrayFromExtra(const ExtraProperty& extra);

} // namespace vis4gs

#endif
