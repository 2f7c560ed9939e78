/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianRasterizer.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianRasterizer
 * @brief   renders a Gaussian scene from one camera with the exact CPU 3DGS rasteriser
 *
 * Input port 0 is a Gaussian scene (vtkPolyData, DESIGN §2); input port 1 is the camera
 * table (one row per view, IO/Scene Vis4GSDataModel.h). The output is a vtkImageData of
 * Width x Height points (spacing 1, origin 0) with point-data arrays
 *  - `RGB` (3 components): the rendered colour C + T*bg, not clamped;
 *  - `Alpha`: accumulated alpha 1 - T;
 *  - `Depth`: alpha-weighted view z, sum of alpha*T*z (divide by Alpha for the expected
 *    depth of the visible surface);
 *  - `Contributors` (unsigned int): the reference's n_contrib.
 * RGB, Alpha and Depth are float arrays in float precision (the reference's arithmetic) and
 * double arrays in double precision.
 *
 * Rows: VTK images grow upwards (row j = 0 at the bottom) while camera images grow
 * downwards, so VTK row j holds camera row Height-1-j. The image therefore displays upright
 * in VTK views, and point (i, j) is pixel (x = i, y = Height-1-j) of the camera image.
 *
 * All numerics are in Core/Render (Rasterizer.h); this class converts and calls it. Gaussians
 * with NaN/Inf parameters are skipped; their count is available after an update.
 */
#ifndef vtkGaussianRasterizer_h
#define vtkGaussianRasterizer_h

#include "vis4gsFiltersRasterModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <string> // For CameraName

class vtkTable;

class VIS4GSFILTERSRASTER_EXPORT vtkGaussianRasterizer : public vtkImageAlgorithm
{
public:
  static vtkGaussianRasterizer* New();
  vtkTypeMacro(vtkGaussianRasterizer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The camera table (input port 1).
   */
  void SetCamerasData(vtkTable* cameras);
  void SetCamerasConnection(vtkAlgorithmOutput* output);

  ///@{
  /**
   * Row of the camera table to render. Default 0. Ignored when CameraName is set.
   */
  vtkSetClampMacro(CameraIndex, int, 0, VTK_INT_MAX);
  vtkGetMacro(CameraIndex, int);
  ///@}

  ///@{
  /**
   * Name of the camera to render (the table's Name column). Default empty: use CameraIndex.
   */
  vtkSetStdStringFromCharMacro(CameraName);
  vtkGetCharFromStdStringMacro(CameraName);
  ///@}

  ///@{
  /**
   * Output size in pixels; 0 (default) keeps the camera's. Another size keeps the field of
   * view (the focal lengths are scaled), as the trainer does when it downsamples.
   */
  vtkSetClampMacro(Width, int, 0, 65536);
  vtkGetMacro(Width, int);
  vtkSetClampMacro(Height, int, 0, 65536);
  vtkGetMacro(Height, int);
  ///@}

  ///@{
  /**
   * Background colour. Default black (0, 0, 0).
   */
  vtkSetVector3Macro(Background, double);
  vtkGetVector3Macro(Background, double);
  ///@}

  ///@{
  /**
   * Active SH degree; -1 (default) uses every degree the scene holds.
   */
  vtkSetClampMacro(SHDegree, int, -1, 3);
  vtkGetMacro(SHDegree, int);
  ///@}

  ///@{
  /**
   * Arithmetic: FLOAT (default, as the reference CUDA rasteriser) or DOUBLE (reference mode).
   */
  enum PrecisionType
  {
    FLOAT = 0,
    DOUBLE = 1
  };
  vtkSetClampMacro(Precision, int, FLOAT, DOUBLE);
  vtkGetMacro(Precision, int);
  void SetPrecisionToFloat() { this->SetPrecision(FLOAT); }
  void SetPrecisionToDouble() { this->SetPrecision(DOUBLE); }
  ///@}

  ///@{
  /**
   * Multiplies every scale (the reference's scale_modifier). Default 1.
   */
  vtkSetClampMacro(ScaleModifier, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ScaleModifier, double);
  ///@}

  ///@{
  /**
   * Threads; 0 (default) uses OpenMP's default.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Results of the last update: Gaussians rendered (survived every cull) and Gaussians skipped
   * because of NaN/Inf parameters or a projection that overflowed.
   */
  vtkGetMacro(NumberOfVisibleGaussians, vtkIdType);
  vtkGetMacro(NumberOfInvalidGaussians, vtkIdType);
  ///@}

  /**
   * Why Gaussians were skipped in the last update, per reason ("3 skipped: 2 with a NaN
   * parameter, 1 with an infinite position"; Documentation/special-values.md), followed by
   * the special values drawn as the reference draws them; empty when there is nothing to say.
   */
  const char* GetSpecialValuesSummary() const { return this->SpecialValuesSummary.c_str(); }

protected:
  vtkGaussianRasterizer();
  ~vtkGaussianRasterizer() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int CameraIndex = 0;
  std::string CameraName;
  int Width = 0;
  int Height = 0;
  double Background[3] = { 0.0, 0.0, 0.0 };
  int SHDegree = -1;
  int Precision = FLOAT;
  double ScaleModifier = 1.0;
  int NumberOfThreads = 0;
  vtkIdType NumberOfVisibleGaussians = 0;
  vtkIdType NumberOfInvalidGaussians = 0;
  std::string SpecialValuesSummary;

private:
  vtkGaussianRasterizer(const vtkGaussianRasterizer&) = delete;
  void operator=(const vtkGaussianRasterizer&) = delete;
};

#endif
