/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSceneReader.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianSceneReader
 * @brief   Reads a 3DGS scene (the trainer's PLY, Niantic's SPZ, GaussianSplats3D's .ksplat, an
 * antimatter15 .splat, a PlayCanvas compressed PLY, a SOG, or glTF with KHR_gaussian_splatting)
 * as the Gaussian vtkPolyData of DESIGN §2.
 *
 * The output's points are the means; point data holds the raw parameters (LogScale,
 * Rotation, OpacityLogit, SH coefficient-major), GaussianId (pedigree ids), the activated
 * Opacity and Scale, and every property the model does not interpret (normals, scores) as an
 * array of its own type. float32 values are copied bit-exactly. Files ending in `.splat` are
 * read as antimatter15 splats; the others by content: SPZ (versions 2-4, converted from SPZ's
 * RUB axes to the PLY's), GaussianSplats3D's .ksplat, a SOG v2 scene (a `.sog` zip, a folder
 * holding meta.json, or the meta.json itself), a PlayCanvas/SuperSplat compressed PLY (a PLY
 * with a `chunk` element and packed vertex properties; decoded as splat-transform does), glTF
 * 2.0 with KHR_gaussian_splatting (a GLB, or JSON; node transforms applied, turned from glTF's
 * +Y-up frame into the PLY's axes), anything else as PLY (binary little/big endian or ASCII).
 * Documentation/file-formats.md describes each format.
 *
 * Errors (missing file, truncated data, missing properties, ...) are reported with
 * vtkErrorMacro naming the file and the problem, and the request fails. Gaussians with NaN or
 * infinite values are kept and reported once with vtkWarningMacro; their number is available
 * from GetNumberOfNonFiniteGaussians() after an update.
 *
 * The parsing is done by vis4gs::ReadGaussianScene (Core/Scene/GaussianIO.h).
 */
#ifndef vtkGaussianSceneReader_h
#define vtkGaussianSceneReader_h

#include "vis4gsIOSceneModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

class VIS4GSIOSCENE_EXPORT vtkGaussianSceneReader : public vtkPolyDataAlgorithm
{
public:
  static vtkGaussianSceneReader* New();
  vtkTypeMacro(vtkGaussianSceneReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read (.ply, .compressed.ply, .spz, .ksplat, .splat, .sog, meta.json, a SOG
   * folder, .glb or .gltf). Default: none.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Highest SH degree to load (0..3); a file with fewer coefficients loads what it has.
   * Default: 3.
   */
  vtkSetClampMacro(MaxSHDegree, int, 0, 3);
  vtkGetMacro(MaxSHDegree, int);
  ///@}

  ///@{
  /**
   * Arrays to load; leaving one out saves the time and memory it would take (the positions
   * are always read). Defaults: all on.
   */
  vtkSetMacro(LoadSH, bool);
  vtkGetMacro(LoadSH, bool);
  vtkBooleanMacro(LoadSH, bool);
  vtkSetMacro(LoadScales, bool);
  vtkGetMacro(LoadScales, bool);
  vtkBooleanMacro(LoadScales, bool);
  vtkSetMacro(LoadRotations, bool);
  vtkGetMacro(LoadRotations, bool);
  vtkBooleanMacro(LoadRotations, bool);
  vtkSetMacro(LoadOpacities, bool);
  vtkGetMacro(LoadOpacities, bool);
  vtkBooleanMacro(LoadOpacities, bool);
  /** Properties the model does not interpret (normals, scores, ...). */
  vtkSetMacro(LoadExtras, bool);
  vtkGetMacro(LoadExtras, bool);
  vtkBooleanMacro(LoadExtras, bool);
  ///@}

  ///@{
  /**
   * Add the activated Opacity and Scale arrays. Default: on.
   */
  vtkSetMacro(ActivatedArrays, bool);
  vtkGetMacro(ActivatedArrays, bool);
  vtkBooleanMacro(ActivatedArrays, bool);
  ///@}

  ///@{
  /**
   * Name of an integer property holding the Gaussians' ids (GaussianId). Empty: ids are the
   * row indices. Default: empty.
   */
  vtkSetStdStringFromCharMacro(IdProperty);
  vtkGetCharFromStdStringMacro(IdProperty);
  ///@}

  ///@{
  /**
   * Whether a file without IdProperty is read all the same, its row indices being the ids (the
   * commands read a scene "with its ids when it has them", vis4gs::IdsFromExtraProperty). The
   * property is then kept as an extra array too. Default: off (a file without it is an error).
   */
  vtkSetMacro(IdPropertyOptional, bool);
  vtkGetMacro(IdPropertyOptional, bool);
  vtkBooleanMacro(IdPropertyOptional, bool);
  ///@}

  ///@{
  /**
   * Facts about the last file read: its SH degree, its format ("binary_little_endian",
   * "binary_big_endian", "ascii", "splat", "ksplat", "compressed_ply", "sog", or "spz v2".."spz
   * v4", followed by " antialiased" when the SPZ header says so), and the number of Gaussians
   * holding a NaN or infinite value (in a compressed PLY, an alpha of 0 or 255 is an opacity
   * logit of -inf or +inf).
   */
  vtkGetMacro(FileSHDegree, int);
  vtkGetCharFromStdStringMacro(FileFormat);
  vtkGetMacro(NumberOfNonFiniteGaussians, vtkIdType);
  ///@}

protected:
  vtkGaussianSceneReader();
  ~vtkGaussianSceneReader() override = default;

  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  std::string FileName;
  int MaxSHDegree = 3;
  bool LoadSH = true;
  bool LoadScales = true;
  bool LoadRotations = true;
  bool LoadOpacities = true;
  bool LoadExtras = true;
  bool ActivatedArrays = true;
  std::string IdProperty;
  bool IdPropertyOptional = false;
  int FileSHDegree = 0;
  std::string FileFormat;
  vtkIdType NumberOfNonFiniteGaussians = 0;

private:
  vtkGaussianSceneReader(const vtkGaussianSceneReader&) = delete;
  void operator=(const vtkGaussianSceneReader&) = delete;
};

#endif
