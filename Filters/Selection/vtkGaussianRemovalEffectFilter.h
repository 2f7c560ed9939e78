/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianRemovalEffectFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianRemovalEffectFilter
 * @brief   Before / after of deleting a selection of Gaussians (issue 20): every training and
 *          test view rendered with and without them and measured against its image.
 *
 * The measurement is Core/Selection/RemovalEffect.h's MeasureRemovalEffect(), the one
 * `vis4gs analyze --select=RULE --report` makes, so the figures are those of its
 * before-after.csv: PSNR, SSIM (11x11 Gaussian window) and L1 of the render clamped to [0, 1]
 * against the image, as the trainer logs them. A view no removed Gaussian takes part in is not
 * rendered again (its "after" is its "before", bit for bit), and with ReuseTiles only the tiles
 * the removal changes are.
 *
 * Input port 0 is a Gaussian scene (vtkPolyData, DESIGN §2). The Gaussians removed are those
 * whose GaussianId is in RemovedIds when it is set, else those where the point-data array
 * RemovalArrayName is non-zero (default "RuleSelected", vtkGaussianRuleSelectionFilter's Mark
 * output). Input port 1 is the camera table (Vis4GSDataModel.h); the images are found as
 * vtkGaussianArtifactScoreFilter finds them (Vis4GSTrainingImages.h: the table's Image column,
 * the images inside the training log the table names, or ImageDirectory by camera name).
 *
 * Output port 0, a vtkTable with one row per view measured, the largest PSNR drop first (views
 * without an image last, NaN figures): view, camera, split, affected, psnr_before, psnr_after,
 * ssim_before, ssim_after, l1_before, l1_after (vis4gs::arrays::Removal*). Output port 1, the
 * totals: one row per split ("train", "test") with split, views (views with an image), affected
 * (views changed) and the means of the figures over those views.
 *
 * The "before" does not depend on the selection: with ReuseTiles, the filter keeps it, per
 * tile, and a later update that only changes the selection (RemovedIds, the marks array's
 * values in a new input of the same Gaussians count as a new input) renders only the "after"
 * of the views the new selection touches (GetBaselineReused()). A "before" made elsewhere for
 * the same input (the score pass's, which renders every training view at full resolution, or
 * an earlier filter's) can be given (SetBaseline(), C++): the filter then renders "before" only
 * the views it lacks, and hands the completed one on (GetMeasuredBaseline()), so that a
 * client running a filter per measurement (the application's clean-up panel) renders no view
 * "before" twice. A removal that cannot be measured (no camera table, an image of the wrong
 * size, an unreadable image, a given "before" of another scene) is an error naming the
 * problem, and the outputs are empty.
 *
 * Output port 2, with PreviewView set, is that camera's renders before and after the removal
 * (vtkImageData of the camera's size, point-data arrays GetPreviewBeforeArrayName() and
 * GetPreviewAfterArrayName(): float RGB, clamped to [0, 1] as measured, rows bottom first as VTK
 * images are; field data RemovalCamera and RemovalView name the camera): what the panel shows for
 * a view picked in its table. An update that only changes PreviewView renders the two images
 * alone: the tables of the same input and selection are kept, not measured again.
 */
#ifndef vtkGaussianRemovalEffectFilter_h
#define vtkGaussianRemovalEffectFilter_h

#include "vis4gsFiltersSelectionModule.h" // For export macro
#include "vtkTableAlgorithm.h"

#include <string> // For RemovalArrayName, ImageDirectory

#ifndef __VTK_WRAP__
#include <memory> // For SetBaseline
#include <vector> // For ViewsOfTable
namespace vis4gs
{
struct Image;
struct RemovalBaseline;
struct RemovalEffect;
struct RemovalViewEffect;
}
#endif

class vtkIdTypeArray;
class vtkImageData;
class vtkTable;

class VIS4GSFILTERSSELECTION_EXPORT vtkGaussianRemovalEffectFilter : public vtkTableAlgorithm
{
public:
  static vtkGaussianRemovalEffectFilter* New();
  vtkTypeMacro(vtkGaussianRemovalEffectFilter, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera table (input port 1).
  void SetCamerasData(vtkDataObject* cameras) { this->SetInputData(1, cameras); }
  void SetCamerasConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  ///@}

  ///@{
  /// The point-data array marking the Gaussians to remove (non-zero). Default "RuleSelected".
  vtkSetStdStringFromCharMacro(RemovalArrayName);
  vtkGetCharFromStdStringMacro(RemovalArrayName);
  ///@}

  ///@{
  /// GaussianId values of the Gaussians to remove; when set, RemovalArrayName is not read.
  /// Default none.
  void SetRemovedIds(vtkIdTypeArray* ids);
  vtkGetObjectMacro(RemovedIds, vtkIdTypeArray);
  ///@}

  ///@{
  /// Folder of the images, matched to the cameras by name. Default empty: the camera table's.
  vtkSetStdStringFromCharMacro(ImageDirectory);
  vtkGetCharFromStdStringMacro(ImageDirectory);
  ///@}

  ///@{
  /// Measure the training views / the test views. Default on, both.
  vtkSetMacro(TrainViews, bool);
  vtkGetMacro(TrainViews, bool);
  vtkBooleanMacro(TrainViews, bool);
  vtkSetMacro(TestViews, bool);
  vtkGetMacro(TestViews, bool);
  vtkBooleanMacro(TestViews, bool);
  ///@}

  ///@{
  /// Background colour of the renders (also behind transparent image pixels). Default black,
  /// the trainer's.
  vtkSetVector3Macro(Background, double);
  vtkGetVector3Macro(Background, double);
  ///@}

  ///@{
  /// Active SH degree of the renders; -1 (default) every degree the scene holds.
  vtkSetClampMacro(SHDegree, int, -1, 3);
  vtkGetMacro(SHDegree, int);
  ///@}

  ///@{
  /// Re-render only the tiles the removal changes (default on; the figures equal a full
  /// re-render's measured per tile, bit for bit). Off renders every affected view whole, as the
  /// first implementation did (the figures agree to about 1e-15 relative).
  vtkSetMacro(ReuseTiles, bool);
  vtkGetMacro(ReuseTiles, bool);
  vtkBooleanMacro(ReuseTiles, bool);
  ///@}

  ///@{
  /// OpenMP threads; 0 (default) uses OpenMP's default.
  vtkSetClampMacro(Threads, int, 0, VTK_INT_MAX);
  vtkGetMacro(Threads, int);
  ///@}

  ///@{
  /// The camera (index in the camera table) whose renders before and after the removal output
  /// port 2 holds. Default -1: none (port 2 is an empty image, nothing is rendered for it).
  vtkSetClampMacro(PreviewView, vtkIdType, -1, VTK_ID_MAX);
  vtkGetMacro(PreviewView, vtkIdType);
  ///@}

  /// Output port 2 (the preview renders) after an update.
  vtkImageData* GetPreviewOutput();

  /// The point-data arrays of output port 2.
  static const char* GetPreviewBeforeArrayName() { return "RemovalPreviewBefore"; }
  static const char* GetPreviewAfterArrayName() { return "RemovalPreviewAfter"; }

#ifndef __VTK_WRAP__
  ///@{
  /**
   * A "before" per tile made elsewhere for this input and camera table, with the filter's
   * rasteriser settings (vis4gs::RemovalBaselineRecorder in the score pass, or another filter's
   * GetMeasuredBaseline()); C++ only. Views it holds are not rendered "before"; the wanted
   * views with an image it lacks are rendered and added to a copy. One made for another number
   * of Gaussians or cameras, or with other rasteriser settings, is an error; an empty one (no
   * views) is none. Used with ReuseTiles only. Default null: the filter renders the "before" of
   * every view itself (once per input).
   */
  void SetBaseline(std::shared_ptr<const vis4gs::RemovalBaseline> baseline);
  std::shared_ptr<const vis4gs::RemovalBaseline> GetBaseline() const;
  ///@}

  /// After an update with ReuseTiles: the "before" the measurement used (the given one
  /// completed), for a later measurement of the same input; null otherwise.
  std::shared_ptr<const vis4gs::RemovalBaseline> GetMeasuredBaseline() const;

  /**
   * The Core form of the two tables (output ports 0 and 1) and the figures after an update
   * (GetNumberRemoved(), ...), for clients that present the measurement (the panel's table,
   * `vis4gs analyze --report`): every field of vis4gs::RemovalEffect but SecondsBefore, which
   * is GetSecondsBefore() less the "before" rendered for a given baseline. False (and @p error)
   * when the tables are not this filter's.
   */
  bool GetEffect(vis4gs::RemovalEffect& effect, std::string* error = nullptr);

  /**
   * The rows of a table of output port 0 in Core's form (camera index, name, split, affected,
   * figures; HasImage where the figures are not NaN), e.g. for vtkGaussianFineTuneFilter's
   * removal figures. False (and @p error) when @p views lacks one of the columns.
   */
  /**
   * The render before (@p before) or after of an output of port 2 as a Core image (rows top
   * first, as the camera's images). False (and @p image empty) when @p preview holds none.
   */
  static bool PreviewImage(vtkImageData* preview, bool before, vis4gs::Image& image);

  static bool ViewsOfTable(vtkTable* views,
    std::vector<vis4gs::RemovalViewEffect>& rows,
    std::string* error = nullptr);
#endif

  ///@{
  /// After an update: Gaussians removed and kept, renders made (before and after, whole or in
  /// part), tiles rendered again for the affected views and the tiles of those views, views
  /// skipped for lack of an image, and the seconds spent on the "before" and the "after".
  vtkGetMacro(NumberRemoved, vtkIdType);
  vtkGetMacro(NumberKept, vtkIdType);
  vtkGetMacro(NumberOfViewsRendered, vtkIdType);
  vtkGetMacro(NumberOfTilesRendered, vtkIdType);
  vtkGetMacro(NumberOfTilesOfTiledViews, vtkIdType);
  vtkGetMacro(NumberOfViewsWithoutImage, vtkIdType);
  vtkGetMacro(SecondsBefore, double);
  vtkGetMacro(SecondsAfter, double);
  ///@}

  ///@{
  /// After an update with ReuseTiles: views whose "before" was taken from the given or kept
  /// baseline, and views whose "before" this update rendered (both 0 when the tables were
  /// kept for a new PreviewView).
  vtkGetMacro(NumberOfBaselineViewsReused, vtkIdType);
  vtkGetMacro(NumberOfBaselineViewsRendered, vtkIdType);
  ///@}

  /// The filter's modification time, RemovedIds' included.
  vtkMTimeType GetMTime() override;

  /// After an update: whether the "before" of the previous update was reused (same input,
  /// cameras and settings; only the selection changed).
  vtkGetMacro(BaselineReused, bool);

protected:
  vtkGaussianRemovalEffectFilter();
  ~vtkGaussianRemovalEffectFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  std::string RemovalArrayName = "RuleSelected";
  vtkIdTypeArray* RemovedIds = nullptr;
  std::string ImageDirectory;
  bool TrainViews = true;
  bool TestViews = true;
  double Background[3] = { 0, 0, 0 };
  int SHDegree = -1;
  bool ReuseTiles = true;
  int Threads = 0;
  vtkIdType PreviewView = -1;
  vtkIdType NumberRemoved = 0;
  vtkIdType NumberKept = 0;
  vtkIdType NumberOfViewsRendered = 0;
  vtkIdType NumberOfTilesRendered = 0;
  vtkIdType NumberOfTilesOfTiledViews = 0;
  vtkIdType NumberOfViewsWithoutImage = 0;
  double SecondsBefore = 0;
  double SecondsAfter = 0;
  vtkIdType NumberOfBaselineViewsReused = 0;
  vtkIdType NumberOfBaselineViewsRendered = 0;
  bool BaselineReused = false;

private:
  struct vtkInternals;
  vtkInternals* Internals;

  vtkGaussianRemovalEffectFilter(const vtkGaussianRemovalEffectFilter&) = delete;
  void operator=(const vtkGaussianRemovalEffectFilter&) = delete;
};

#endif
