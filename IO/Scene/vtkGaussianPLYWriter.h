/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianPLYWriter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianPLYWriter
 * @brief   Writes a Gaussian vtkPolyData (DESIGN §2) as a 3DGS PLY that the original trainer
 * and viewers read.
 *
 * Properties are written in the trainer's order (x y z, normals when the input has nx/ny/nz
 * arrays, f_dc, f_rest channel-major, opacity, scale, rot) as float32, bit-exactly. Every
 * other point-data array (scores such as ViewCoverage or BlurScore, other tools' properties)
 * becomes extra PLY properties of its own type after the standard ones; an array of several
 * components becomes `<name>_0`, `<name>_1`, ... The activated Opacity and Scale arrays are
 * not written (they are derived). GaussianId is written as an `id` property only with
 * WriteIds on.
 *
 * A FileName ending in `.glb` / `.gltf` (glTF KHR_gaussian_splatting), `.spz`,
 * `.compressed.ply` or `.splat` writes that format instead, as every interface chooses it
 * (vis4gs::WriteGaussianScene): extras and ids only where the format holds them (glTF), the
 * quantisation error measured by reading back in GetWriteReport().
 *
 * The file is written to a temporary file in the same folder and renamed into place, so a
 * failed write never leaves a half-written file. Errors are reported with vtkErrorMacro.
 * The writing is done by vis4gs::WriteGaussianScene (Core/Scene/GaussianIO.h).
 */
#ifndef vtkGaussianPLYWriter_h
#define vtkGaussianPLYWriter_h

#include "vis4gsIOSceneModule.h" // For export macro
#include "vtkWriter.h"

#include <string> // For std::string

class vtkPolyData;

class VIS4GSIOSCENE_EXPORT vtkGaussianPLYWriter : public vtkWriter
{
public:
  static vtkGaussianPLYWriter* New();
  vtkTypeMacro(vtkGaussianPLYWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum FileFormats
  {
    BINARY_LITTLE_ENDIAN = 0,
    BINARY_BIG_ENDIAN = 1,
    ASCII = 2
  };

  ///@{
  /**
   * The file to write. Default: none.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * PLY encoding: BINARY_LITTLE_ENDIAN (the trainer's), BINARY_BIG_ENDIAN or ASCII.
   * Default: BINARY_LITTLE_ENDIAN.
   */
  vtkSetClampMacro(FileFormat, int, BINARY_LITTLE_ENDIAN, ASCII);
  vtkGetMacro(FileFormat, int);
  void SetFileFormatToBinaryLittleEndian() { this->SetFileFormat(BINARY_LITTLE_ENDIAN); }
  void SetFileFormatToBinaryBigEndian() { this->SetFileFormat(BINARY_BIG_ENDIAN); }
  void SetFileFormatToASCII() { this->SetFileFormat(ASCII); }
  ///@}

  ///@{
  /**
   * Write the GaussianId array as an integer property named IdPropertyName. Default: off.
   */
  vtkSetMacro(WriteIds, bool);
  vtkGetMacro(WriteIds, bool);
  vtkBooleanMacro(WriteIds, bool);
  vtkSetStdStringFromCharMacro(IdPropertyName);
  vtkGetCharFromStdStringMacro(IdPropertyName);
  ///@}

  ///@{
  /**
   * Write point-data arrays that are not part of the model as extra properties.
   * Default: on.
   */
  vtkSetMacro(WriteExtraArrays, bool);
  vtkGetMacro(WriteExtraArrays, bool);
  vtkBooleanMacro(WriteExtraArrays, bool);
  ///@}

  /**
   * The input Gaussian scene.
   */
  vtkPolyData* GetInput();

  /**
   * After a write: one line saying what was written and, for a lossy format, its measured
   * quantisation error and what was left out. Empty before the first write.
   */
  const char* GetWriteReport() const { return this->WriteReport.c_str(); }

protected:
  vtkGaussianPLYWriter() = default;
  ~vtkGaussianPLYWriter() override = default;

  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  std::string FileName;
  int FileFormat = BINARY_LITTLE_ENDIAN;
  bool WriteIds = false;
  std::string IdPropertyName = "id";
  bool WriteExtraArrays = true;
  std::string WriteReport;

private:
  vtkGaussianPLYWriter(const vtkGaussianPLYWriter&) = delete;
  void operator=(const vtkGaussianPLYWriter&) = delete;
};

#endif
