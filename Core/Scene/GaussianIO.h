// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file GaussianIO.h
 * @brief Reading and writing 3DGS scenes: the trainer's PLY (binary little/big endian and
 * ASCII), the antimatter15 `.splat` format (reference §1.1), Niantic's SPZ, GaussianSplats3D's
 * `.ksplat`, PlayCanvas's compressed PLY and SOG, and glTF with KHR_gaussian_splatting.
 *
 * PLY properties are looked up by name in any order; every PLY scalar type name is accepted
 * (char/int8, uchar/uint8, short/int16, ushort/uint16, int/int32, uint/uint32,
 * float/float32, double/float64). float32 values are copied bit for bit (NaN payloads
 * included). The SH degree (0..3) is inferred from the number of `f_rest_*` properties, which
 * the file stores channel-major (all R, then G, then B); GaussianCloud::SH is
 * coefficient-major. Per-vertex properties the model does not interpret (normals, scores,
 * other tools' fields) are kept as GaussianCloud::Extra with their type and written back.
 *
 * Errors (unreadable file, truncated data, a header count larger than the file, missing
 * required properties, non-numeric ASCII, ...) throw std::runtime_error whose message starts
 * with the file name. NaN/Inf parameters are not an error: they are kept, and counted in the
 * GaussianReadReport so the caller can warn. Nothing is allocated before the header's counts
 * are checked against the file size.
 */
#ifndef vis4gs_GaussianIO_h
#define vis4gs_GaussianIO_h

#include "GaussianCloud.h"
#include "GaussianMath.h"

#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vis4gs
{

/// What a read should load. Arrays left out stay empty in the GaussianCloud.
struct GaussianReadOptions
{
  /// Highest SH degree to load (0..3); a file with fewer coefficients loads what it has.
  int MaxShDegree = 3;
  bool LoadPositions = true;
  bool LoadScales = true;
  bool LoadRotations = true;
  bool LoadOpacities = true;
  bool LoadSH = true;
  /// Keep unknown per-vertex properties as GaussianCloud::Extra.
  bool LoadExtras = true;
  /// If not empty: fill GaussianCloud::Ids from this property (integer valued; it is then not
  /// kept as an extra). A file without it gives an error.
  std::string IdProperty;
};

/// What a read found besides the data.
struct GaussianReadReport
{
  std::string Format;   ///< "binary_little_endian", "binary_big_endian", "ascii", "splat"
  int FileShDegree = 0; ///< SH degree stored in the file
  /// Non-finite (NaN or +-Inf) values among the loaded parameters, and Gaussians with at
  /// least one. The values are kept as read.
  std::size_t NonFiniteValues = 0;
  std::size_t NonFiniteGaussians = 0;
  /// The render mode the file names: "default", "antialiased" (Mip-Splatting's 2D filter:
  /// Brush's `SplatRenderMode: mip`, Postshot's `antialiased 1`, SPZ's flag) or "2dgs" (2D
  /// Gaussian splatting surfels: Brush's `SplatRenderMode: 2dgs`, or a PLY without scale_2);
  /// empty when the file says nothing.
  std::string RenderMode;
  /// Human-readable warnings (already formatted with the file name).
  std::vector<std::string> Warnings;
};

/// Reads a 3DGS PLY file.
GaussianCloud ReadGaussianPly(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);

/// Reads a 3DGS PLY from memory; @p name is used in error messages (used by fuzzers/tests).
GaussianCloud ReadGaussianPlyFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);

enum class PlyFormat
{
  BinaryLittleEndian,
  BinaryBigEndian,
  Ascii
};

struct GaussianWriteOptions
{
  PlyFormat Format = PlyFormat::BinaryLittleEndian;
  /// Name of the property that stores GaussianCloud::Ids when they are not empty
  /// (int32 when every id fits, float64 otherwise: PLY has no 64-bit integer type).
  std::string IdProperty = "id";
  /// Write GaussianCloud::Ids (when not empty). Off for a cloud whose ids are its row
  /// numbers, given by a reader, that the file it came from does not hold. Default on.
  bool WriteIds = true;
  /// Comment lines written into the header.
  std::vector<std::string> Comments;
  /// Properties written after the cloud's own extras (before the ids), so that a caller adds
  /// columns (scores) without copying a cloud of gigabytes. Default none.
  const std::vector<ExtraProperty>* AppendedExtras = nullptr;
};

/**
 * Writes @p cloud as a 3DGS PLY: properties in the trainer's order x y z [nx ny nz] f_dc_0..2
 * f_rest_* (channel-major) opacity scale_0..2 rot_0..3, then the remaining extras, then the
 * ids. Standard arrays are float32; extras keep their type; normals are written only when the
 * cloud holds them as extras (the trainer's loader never reads them). Arrays that are empty
 * (not loaded) are left out. The file is written to a temporary file in the same folder and
 * renamed into place, so a failed write never leaves a half-written @p path.
 *
 * ASCII writes the shortest decimal that reads back to the same float; float32 NaNs other
 * than the default quiet NaN are written as `nan(0x<payload>)` (which this reader restores bit
 * for bit). float64 extras in ASCII keep their value but not a NaN payload.
 */
void WriteGaussianPly(const std::string& path,
  const GaussianCloud& cloud,
  const GaussianWriteOptions& options = {});

/// Same as WriteGaussianPly, into memory.
std::vector<unsigned char> WriteGaussianPlyToMemory(const GaussianCloud& cloud,
  const GaussianWriteOptions& options = {});

/**
 * Reads an antimatter15 `.splat` file (32 bytes per Gaussian: 3 float32 position, 3 float32
 * linear scale, RGBA uint8, quaternion uint8 w x y z as (q-128)/128) and converts it to raw
 * parameters: log scale, opacity logit of alpha/255 clamped to [1e-4, 1-1e-4], SH DC
 * (c/255-0.5)/C0, SH degree 0. A size that is not a multiple of 32 is an error.
 */
GaussianCloud ReadSplat(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
GaussianCloud ReadSplatFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);

/// Writes the antimatter15 `.splat` format (quantising colour, opacity and rotation; used by
/// tests and exports, never for analysis). Gaussians the reference cannot draw
/// (ClassifyGaussian, or a non-finite DC colour) are left out; returns how many were.
std::size_t WriteSplat(const std::string& path, const GaussianCloud& cloud);

/**
 * Reads Niantic's SPZ (versions 2 and 3: one gzip stream; version 4: zstd streams behind a
 * table of contents; Documentation/file-formats.md, "SPZ"). Decoding follows the format's
 * definition: 24-bit fixed-point positions, log-scales byte/16-10, opacity logit of byte/255
 * (clamped to [1e-6, 1-1e-6] as splat-transform does), DC colour (byte/255-0.5)/0.15, SH
 * (byte-128)/128, rotations as 3 bytes xyz (v2) or smallest-three in 4 bytes (v3+). SPZ
 * stores RUB axes unless Adobe's coordinate-system extension says otherwise; positions,
 * quaternions and SH are converted to the INRIA PLY axes (RDF): y and z change sign, the
 * quaternion's y and z, and the SH coefficients odd in y xor z. Only the SH degree asked for
 * is decoded (a degree-4 file gives at most degree 3). Counts and sizes are checked against
 * the file before anything is allocated; a file that claims more than 1032 times its size
 * once decompressed is refused. Errors name the file and the problem.
 */
GaussianCloud ReadSpz(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
GaussianCloud ReadSpzFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);

/// True if @p path starts like an SPZ file (a gzip stream or an "NGSP" header).
bool IsSpzFile(const std::string& path);

struct SpzWriteOptions
{
  /// Fractional bits of the 24-bit fixed-point positions; -1 picks the most that fit the
  /// scene's largest coordinate (Niantic's writer always uses 12).
  int FractionalBits = -1;
  /// Bits kept of the 8-bit SH bytes, degree 1 and degrees 2-3 (the reference's defaults).
  int Sh1Bits = 5;
  int ShRestBits = 4;
  /// Sets the header's antialiased flag.
  bool Antialiased = false;
  int ZstdLevel = 12;
};

/// Largest and root-mean-square absolute difference between the source and what reads back.
struct SpzAttributeError
{
  double Max = 0;
  double Rms = 0;
};

struct SpzWriteReport
{
  std::size_t Written = 0;
  /// Gaussians left out: not drawable (ClassifyGaussian), non-finite SH, or OutOfRange.
  std::size_t LeftOut = 0;
  std::size_t OutOfRange = 0; ///< a coordinate beyond 2^23: no fixed point holds it
  /// Drawable special values written with their meaning and left out of the errors:
  /// opacity logit +-inf (bytes 255/0), log-scale -inf (stored as -10), zero quaternions
  /// (stored as the identity).
  std::size_t SpecialValues = 0;
  int FractionalBits = 0;
  std::size_t FileBytes = 0;
  SpzAttributeError Position; ///< scene units, per component
  SpzAttributeError LogScale; ///< natural log
  SpzAttributeError Rotation; ///< unit quaternion components, sign aligned
  SpzAttributeError Opacity;  ///< sigmoid(logit), 0..1
  SpzAttributeError Color;    ///< SH DC coefficients
  SpzAttributeError SH;       ///< higher SH coefficients
};

/**
 * Writes SPZ version 4 in RUB axes (the format's default), zstd streams, no extensions.
 * Gaussians the reference cannot draw (ClassifyGaussian), with a non-finite SH coefficient,
 * or with a coordinate beyond 2^23 are left out and counted, as WriteSplat does; drawable
 * special values keep their meaning. Returns the quantisation error per attribute, measured
 * by decoding what was written. Written through a temporary file renamed into place.
 */
/// One line: written / left out counts, special values and max/RMS error per attribute.
std::string DescribeQuantisation(const SpzWriteReport& report);

SpzWriteReport WriteSpz(const std::string& path,
  const GaussianCloud& cloud,
  const SpzWriteOptions& options = {});
std::vector<unsigned char> WriteSpzToMemory(const GaussianCloud& cloud,
  const SpzWriteOptions& options = {},
  SpzWriteReport* report = nullptr);

/**
 * The PlayCanvas / SuperSplat compressed PLY (Documentation/file-formats.md): chunks of 256
 * Gaussians with float32 bounds (12 or 18 per chunk), 11-10-11 position and log-scale,
 * 2-10-10-10 smallest-three rotation, 8-8-8-8 colour and opacity, optional uint8 f_rest in an
 * `sh` element. Decoded as splat-transform decodes it (each value computed in double, rounded
 * once to float32): colour c -> SH DC (c - 0.5)/C0, alpha byte w -> logit -log(255/w - 1)
 * (0 and 255 give -inf and +inf), SH byte b -> ((b+0.5)/256 - 0.5)*8 (0 -> -4, 255 -> 4).
 * Only the SH degree asked for is decoded. Counts are checked against each other (chunks =
 * ceil(vertices/256), sh rows = vertices) and against the file size before allocating.
 */
GaussianCloud ReadCompressedPly(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
GaussianCloud ReadCompressedPlyFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
/// True when @p head (the start of a file) is a PLY header with a `chunk` element and a
/// `packed_position` vertex property.
bool IsCompressedPly(const void* head, std::size_t size);

struct CompressedPlyWriteOptions
{
  /// Write in the reference writer's Morton order (smaller chunk bounds, so smaller errors);
  /// false keeps the cloud's order.
  bool MortonOrder = true;
  /// Highest SH degree written (the cloud's if lower).
  int MaxShDegree = 3;
  std::vector<std::string> Comments;
};

/// Max and RMS of |decoded - source| over the written values of one attribute.
struct QuantisationError
{
  std::string Attribute;
  double Max = 0;
  double Rms = 0;
  std::size_t Values = 0;
};

struct CompressedPlyWriteReport
{
  std::size_t Written = 0;
  /// Gaussians the reference cannot draw (ClassifyGaussian, or inf/NaN in a written SH
  /// coefficient): left out, as by WriteSplat.
  std::size_t LeftOut = 0;
  /// Source index of each written Gaussian, in file order.
  std::vector<std::size_t> Order;
  /// position, log-scale, rotation (degrees between the normalised quaternions), f_dc,
  /// opacity (alpha = sigmoid of the logit), f_rest.
  std::vector<QuantisationError> Errors;
  /// Log-scale components outside the format's [-20, 20] (-inf included: written as -20) and
  /// f_rest outside [-4, 4]; both are clamped and left out of the errors above.
  std::size_t ClampedLogScales = 0;
  std::size_t ClampedSH = 0;
};

/**
 * Writes the compressed PLY as splat-transform 3.2 does (18-float chunks, same packing and
 * rounding). Opacity logits +-inf are written as alpha 0 / 255 and read back as +-inf; a
 * zero quaternion as the identity (the rotation the renderer gives it); a log-scale of -inf as
 * -20 (scale 2e-9, drawn as the same dilated point). Ids and extras are not stored. Written to
 * a temporary file and renamed into place.
 */
CompressedPlyWriteReport WriteCompressedPly(const std::string& path,
  const GaussianCloud& cloud,
  const CompressedPlyWriteOptions& options = {});
std::vector<unsigned char> WriteCompressedPlyToMemory(const GaussianCloud& cloud,
  const CompressedPlyWriteOptions& options = {},
  CompressedPlyWriteReport* report = nullptr);
/// One line: written / left out counts and max/RMS error per attribute.
std::string DescribeQuantisation(const CompressedPlyWriteReport& report);

/**
 * Reads a PlayCanvas SOG v2 scene (Documentation/file-formats.md): @p path is a `.sog` zip
 * archive, a folder holding meta.json, or a meta.json file with its WebP textures beside it.
 * Decoded as splat-transform decodes it (each value computed in double, rounded once to
 * float32): positions from the 16-bit means through the inverse log transform, smallest-three
 * quaternions, codebook log-scales and SH DC, opacity logit log(a/(1-a)) of the alpha clamped
 * to [1e-6, 1-1e-6] (so at most +-13.8), f_rest from the palette (16-bit labels). Only the SH
 * degree asked for is decoded. Textures are checked against meta.json's count (at least
 * count, at most 2*count+65536 texels) before decoding, and a texture or zip entry that
 * expands more than 1024 times past 64 MiB is refused as a decompression bomb.
 */
GaussianCloud ReadSog(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
/// Same, from a `.sog` archive in memory (fuzzers, tests); @p name is used in messages.
GaussianCloud ReadSogZipFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
/// Same, from files in memory by name ("meta.json" and the textures it names).
GaussianCloud ReadSogFromMemoryFiles(const std::map<std::string, std::vector<unsigned char>>& files,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
/// True for a folder holding meta.json, a zip archive, or a JSON file naming "means".
bool IsSog(const std::string& path);

/**
 * Reads the `.ksplat` format of mkkellogg/GaussianSplats3D (version 0.x, compression levels
 * 0-2; Documentation/file-formats.md, ".ksplat"): positions float32 (level 0) or 16-bit
 * offsets from float32 bucket centres, linear scales and w x y z quaternions float32 or
 * float16, RGBA bytes, SH float32, float16 or bytes over the header's range. Converted to raw
 * parameters: log scale, opacity logit of alpha/255 clamped to [1e-6, 1-1e-6] (as
 * splat-transform does), SH DC (c/255-0.5)/C0; quaternions and axes as stored (the format
 * keeps the PLY's). Only the SH degree asked for is decoded. Counts and sizes are checked
 * against the file before anything is allocated; errors name the file and the problem.
 */
GaussianCloud ReadKsplat(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
GaussianCloud ReadKsplatFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);

/// True if @p path holds a .ksplat header (version 0.x) whose sections fill the file exactly.
bool IsKsplatFile(const std::string& path);

/**
 * Reads glTF 2.0 with `KHR_gaussian_splatting` (Documentation/file-formats.md, "glTF"): a GLB,
 * or JSON whose buffers are data URIs or files beside it (relative names only). Every
 * primitive with the extension that a node of the default scene instances is read, moved by
 * the node's global transform (the whole hierarchy's matrix or TRS: means, rotations and
 * scales; a transform that scales unevenly or shears has each covariance M S Mᵀ re-factored
 * exactly, with a warning; a mirror or collapse is an error, the extension leaves it undefined),
 * then turned from glTF's frame (+Y up) into the PLY's axes by a half turn about z, as
 * splat-transform's `.glb` writer does in reverse. Attributes as the extension defines them:
 * linear scales (log taken), linear opacity in [0, 1] (logit taken, in double), unit
 * quaternions x y z w, SH coefficients of degrees 0-3 copied bit for bit; the fallback
 * COLOR_0 stands in (with a warning) only when SH degree 0 or the opacity is missing. A
 * primitive whose `KHR_gaussian_splatting` holds `KHR_gaussian_splatting_compression_spz_2` is
 * read from its SPZ payload with ReadSpzFromMemory. Application-specific SCALAR attributes
 * (a leading underscore) become extras of the name without it. Errors name the file and the
 * accessor, buffer or node at fault.
 */
GaussianCloud ReadGltf(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
/// Same from memory; external buffer files cannot be reached (an error names them).
GaussianCloud ReadGltfFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);
/// True for a GLB ("glTF" magic), a `.gltf` holding a JSON object, or a JSON object naming
/// "asset" and KHR_gaussian_splatting in its first MiB.
bool IsGltfFile(const std::string& path);

struct GltfWriteOptions
{
  /// Highest SH degree written (the cloud's if lower).
  int MaxShDegree = 3;
  /// Write the cloud's extras as application-specific SCALAR attributes `_<name>` (8- and
  /// 16-bit integers keep their type, everything else is float32).
  bool KeepExtras = true;
  /// The extension's required colorSpace ("srgb_rec709_display" or "lin_rec709_display").
  std::string ColorSpace = "srgb_rec709_display";
};

struct GltfWriteReport
{
  std::size_t Written = 0;
  /// Gaussians the reference cannot draw (ClassifyGaussian) or with non-finite written SH.
  std::size_t LeftOut = 0;
  std::size_t FileBytes = 0;
  /// What does not read back exactly, measured by reading the written bytes: log-scale (float32
  /// exp then log), rotation (normalised to unit length; degrees), opacity (alpha, float32
  /// sigmoid), extras (float32 of float64 or 32-bit integers); positions and SH are exact.
  std::vector<QuantisationError> Errors;
};

/**
 * Writes glTF 2.0 with `KHR_gaussian_splatting`: a GLB unless @p path ends in `.gltf` (then
 * JSON with the buffer as a data URI). One node, one POINTS primitive: POSITION (with min/max),
 * ROTATION (unit quaternions, a zero one as the identity), SCALE (exp of the log-scale),
 * OPACITY (sigmoid of the logit), SH degrees 0..MaxShDegree, float32 each, the fallback
 * COLOR_0 (8-bit, sRGB decoded to linear as glTF asks), and the extras. Data is turned out of
 * the PLY's axes into glTF's frame (ReadGltf's exact inverse). Gaussians the reference cannot
 * draw are left out and counted, as by WriteSplat; an empty result is an error (glTF accessors
 * hold at least one element). Written to a temporary file and renamed into place.
 */
GltfWriteReport WriteGltf(const std::string& path,
  const GaussianCloud& cloud,
  const GltfWriteOptions& options = {});
/// Same into memory: @p binary a GLB, else JSON with a data URI.
std::vector<unsigned char> WriteGltfToMemory(const GaussianCloud& cloud,
  bool binary,
  const GltfWriteOptions& options = {},
  GltfWriteReport* report = nullptr);
/// One line: written / left out counts and max/RMS error per attribute.
std::string DescribeQuantisation(const GltfWriteReport& report);

/// Reads a scene by content, then extension: .ksplat (IsKsplatFile) with ReadKsplat, SPZ (gzip
/// or "NGSP" start) with ReadSpz, glTF (IsGltfFile) with ReadGltf, a SOG (folder, zip or meta.json)
/// with ReadSog, ".splat" with ReadSplat, a compressed PLY (by content) with ReadCompressedPly,
/// anything else with ReadGaussianPly (GaussianScene.cxx: a new format adds its test there).
GaussianCloud ReadGaussianScene(const std::string& path,
  const GaussianReadOptions& options = {},
  GaussianReadReport* report = nullptr);

/// How WriteGaussianScene writes, whatever the format.
struct SceneWriteOptions
{
  /// Encoding of a `.ply` (the other formats have one each).
  PlyFormat Format = PlyFormat::BinaryLittleEndian;
  /// Property holding GaussianCloud::Ids in a PLY (and `_<name>` in glTF, float32).
  std::string IdProperty = "id";
  /// Highest SH degree written (the cloud's if lower).
  int MaxShDegree = 3;
};

/**
 * Writes @p cloud in the format @p path's name says, as every interface does (`vis4gs
 * convert`, the application's export, vtkGaussianPLYWriter): `.compressed.ply`
 * (WriteCompressedPly), `.spz` (WriteSpz), `.glb` / `.gltf` (WriteGltf), `.splat` (WriteSplat),
 * anything else a 3DGS PLY (WriteGaussianPly, exact). Extras and ids go where the format can
 * hold them (PLY, glTF). Returns one line saying what was written and, for the lossy formats,
 * the error measured by reading it back (DescribeQuantisation) and what was left out.
 */
std::string WriteGaussianScene(const std::string& path,
  const GaussianCloud& cloud,
  const SceneWriteOptions& options = {});

/**
 * Writes @p text to @p path through a temporary file in the same folder renamed into place (as
 * every writer here): a failure (a full disk, a read-only folder) leaves no partial file and a
 * file already at @p path untouched, and throws std::runtime_error naming @p path and the
 * problem. The commands' tables and reports go through it.
 */
void WriteTextFile(const std::string& path, const std::string& text);

namespace detail
{
/// The writers' rule for what a lossy or reduced format keeps: Gaussian @p g is drawn by the
/// reference (ClassifyGaussian) and its first @p coefficients SH coefficients (RGB each), the
/// ones written, are finite; the rest is left out and counted by the writer.
inline bool WritableGaussian(const GaussianCloud& cloud, std::size_t g, std::size_t coefficients)
{
  if (ClassifyGaussian(&cloud.Positions[3 * g],
        &cloud.LogScales[3 * g],
        &cloud.Rotations[4 * g],
        cloud.OpacityLogits[g]) != GaussianClass::Drawn)
  {
    return false;
  }
  const float* sh = &cloud.SH[3 * static_cast<std::size_t>(cloud.ShCoefficientCount()) * g];
  for (std::size_t i = 0; i < 3 * coefficients; ++i)
  {
    if (!std::isfinite(sh[i]))
    {
      return false;
    }
  }
  return true;
}

/// "N Gaussians written, L left out (...); quantisation error max/RMS: a max/rms; ..." for the
/// writers' reports (DescribeQuantisation).
std::string DescribeWriteErrors(std::size_t written,
  std::size_t leftOut,
  const std::vector<QuantisationError>& errors);

/// A copy of @p cloud with its SH cut to @p degree (the whole copy when it holds no more).
GaussianCloud CutShDegree(const GaussianCloud& cloud, int degree);

/// A cloud of @p n Gaussians with SH degree @p shDegree (0 when @p options skip SH) whose
/// arrays are sized for what @p options ask a reader to load, the others left empty: the one
/// allocation rule of every scene reader.
GaussianCloud AllocateReadArrays(std::size_t n, int shDegree, const GaussianReadOptions& options);

/// The end of every scene reader: when the cloud holds non-finite values, the warning "NAME:
/// G Gaussians hold NaN or infinite values (V values<note>); they are kept as read" (@p note
/// says what else the format counts, e.g. ", zero scales included"); then @p report is moved
/// to the caller's @p out, if any.
void FinishReadReport(GaussianReadReport& report,
  const std::string& name,
  GaussianReadReport* out,
  const std::string& note = "");
} // namespace detail

} // namespace vis4gs

#endif
