// SPDX-License-Identifier: BSD-3-Clause
// glTF KHR_gaussian_splatting (issue 34): a file assembled by hand from the extension's text
// with values derived by hand, node transforms checked against the covariance and SH colour
// they must give, the writer's exact round trip, the SPZ payload, and hostile input.
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneFile.h"
#include "SceneTestUtils.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

namespace vis4gs
{
namespace
{

using testing::FileBytes;
using testing::TempDir;
using testing::WriteFile;

using Bytes = std::vector<unsigned char>;

void PutF(Bytes& b, float v)
{
  unsigned char raw[4];
  std::memcpy(raw, &v, 4);
  b.insert(b.end(), raw, raw + 4); // little-endian hosts only (the tests' machines)
}

/// A glTF JSON with one splat primitive whose accessors are consecutive float arrays of
/// @p bin (listed in @p attributes as "SEMANTIC:TYPE"), instanced by @p nodes.
std::string Json(const Bytes& bin,
  const std::vector<std::string>& attributes,
  std::size_t count,
  const std::string& nodes = R"("nodes":[{"mesh":0}])",
  const std::string& primitiveExtra = "")
{
  std::string views, accessors, attrs;
  std::size_t offset = 0;
  for (std::size_t i = 0; i < attributes.size(); ++i)
  {
    const auto colon = attributes[i].rfind(':');
    const std::string semantic = attributes[i].substr(0, colon);
    const std::string type = attributes[i].substr(colon + 1);
    const std::size_t comps = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
    const std::string sep = i ? "," : "";
    views += sep + R"({"buffer":0,"byteOffset":)" + std::to_string(offset) + R"(,"byteLength":)" +
      std::to_string(4 * comps * count) + "}";
    accessors += sep + R"({"bufferView":)" + std::to_string(i) +
      R"(,"componentType":5126,"count":)" + std::to_string(count) + R"(,"type":")" + type + "\"}";
    attrs += sep + "\"" + semantic + "\":" + std::to_string(i);
    offset += 4 * comps * count;
  }
  return R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_gaussian_splatting"],"scene":0,)"
         R"("scenes":[{"nodes":[0]}],)" +
    nodes + R"(,"meshes":[{"primitives":[{"mode":0,"attributes":{)" + attrs +
    R"(},"extensions":{"KHR_gaussian_splatting":{"kernel":"ellipse","colorSpace":"srgb_rec709_display")" +
    primitiveExtra + R"(}}}]}],"buffers":[{"byteLength":)" + std::to_string(bin.size()) +
    R"(,"uri":"data:application/octet-stream;base64,)" +
    detail::EncodeBase64(bin.data(), bin.size()) + R"("}],"bufferViews":[)" + views +
    R"(],"accessors":[)" + accessors + "]}";
}

GaussianCloud FromText(const std::string& json)
{
  return ReadGltfFromMemory(json.data(), json.size(), "test.gltf");
}

/// Two Gaussians with SH degree 1, attribute by attribute as the extension lays them out.
struct HandFile
{
  float Pos[2][3] = { { 1, 2, 3 }, { -4, 0.5f, 8 } };
  float Rot[2][4] = { { 0, 0, 0, 1 }, { 0.5f, 0.5f, 0.5f, 0.5f } }; // x y z w
  float Scale[2][3] = { { 0.5f, 1, 2 }, { 0.01f, 0.02f, 0 } };
  float Opacity[2] = { 0.25f, 1 };
  float Sh[2][4][3];
  Bytes Bin;
  std::vector<std::string> Attributes = { "POSITION:VEC3",
    "KHR_gaussian_splatting:ROTATION:VEC4",
    "KHR_gaussian_splatting:SCALE:VEC3",
    "KHR_gaussian_splatting:OPACITY:SCALAR",
    "KHR_gaussian_splatting:SH_DEGREE_0_COEF_0:VEC3",
    "KHR_gaussian_splatting:SH_DEGREE_1_COEF_0:VEC3",
    "KHR_gaussian_splatting:SH_DEGREE_1_COEF_1:VEC3",
    "KHR_gaussian_splatting:SH_DEGREE_1_COEF_2:VEC3" };

  HandFile()
  {
    for (int g = 0; g < 2; ++g)
    {
      for (int k = 0; k < 4; ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          Sh[g][k][c] = 0.1f * float(1 + g) * float(k + 1) - 0.05f * float(c);
        }
      }
    }
    auto vec = [this](auto& a, int comps)
    {
      for (int g = 0; g < 2; ++g)
      {
        for (int c = 0; c < comps; ++c)
        {
          PutF(this->Bin, a[g][c]);
        }
      }
    };
    vec(Pos, 3);
    vec(Rot, 4);
    vec(Scale, 3);
    PutF(Bin, Opacity[0]);
    PutF(Bin, Opacity[1]);
    for (int k = 0; k < 4; ++k)
    {
      for (int g = 0; g < 2; ++g)
      {
        for (int c = 0; c < 3; ++c)
        {
          PutF(Bin, Sh[g][k][c]);
        }
      }
    }
  }
};

TEST(GaussianGltf, HandAssembledFileDecodesAsTheExtensionDefines)
{
  const HandFile f;
  GaussianReadReport report;
  const std::string json = Json(f.Bin, f.Attributes, 2);
  const GaussianCloud c = ReadGltfFromMemory(json.data(), json.size(), "hand.gltf", {}, &report);
  ASSERT_EQ(c.Count, 2u);
  EXPECT_EQ(c.ShDegree, 1);
  EXPECT_EQ(report.Format, "gltf");
  for (int g = 0; g < 2; ++g)
  {
    // glTF's frame to the PLY's: a half turn about z.
    EXPECT_EQ(c.Positions[3 * g], -f.Pos[g][0]);
    EXPECT_EQ(c.Positions[3 * g + 1], -f.Pos[g][1]);
    EXPECT_EQ(c.Positions[3 * g + 2], f.Pos[g][2]);
    // q_ply = r^-1 q_gltf with r = (w 0, x 0, y 0, z 1): (z, y, -x, -w) of the stored xyzw.
    EXPECT_EQ(c.Rotations[4 * g], f.Rot[g][2]);
    EXPECT_EQ(c.Rotations[4 * g + 1], f.Rot[g][1]);
    EXPECT_EQ(c.Rotations[4 * g + 2], -f.Rot[g][0]);
    EXPECT_EQ(c.Rotations[4 * g + 3], -f.Rot[g][3]);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(c.LogScales[3 * g + k], static_cast<float>(std::log(double(f.Scale[g][k]))));
    }
    EXPECT_EQ(
      c.OpacityLogits[g], static_cast<float>(std::log(f.Opacity[g] / (1.0 - f.Opacity[g]))));
    for (int ch = 0; ch < 3; ++ch)
    {
      EXPECT_EQ(c.SH[12 * g + ch], f.Sh[g][0][ch]);
      EXPECT_EQ(c.SH[12 * g + 3 + ch], -f.Sh[g][1][ch]); // m = -1 (y) turns
      EXPECT_EQ(c.SH[12 * g + 6 + ch], f.Sh[g][2][ch]);  // m = 0 (z) stays
      EXPECT_EQ(c.SH[12 * g + 9 + ch], -f.Sh[g][3][ch]); // m = 1 (x) turns
    }
  }
  EXPECT_TRUE(std::isinf(c.LogScales[5]) && c.LogScales[5] < 0);
  EXPECT_TRUE(std::isinf(c.OpacityLogits[1]) && c.OpacityLogits[1] > 0);
  EXPECT_EQ(report.NonFiniteGaussians, 1u);

  GaussianReadOptions dcOnly;
  dcOnly.MaxShDegree = 0;
  dcOnly.LoadRotations = false;
  const GaussianCloud d = ReadGltfFromMemory(json.data(), json.size(), "hand.gltf", dcOnly);
  EXPECT_EQ(d.ShDegree, 0);
  EXPECT_TRUE(d.Rotations.empty());
  EXPECT_EQ(d.SH[3], f.Sh[1][0][0]);
}

TEST(GaussianGltf, TheColourIsInvariantUnderTheAxisChange)
{
  // The same Gaussian seen from the same (turned) direction gives the same colour: checks the
  // SH sign flips against the basis, independently of the table in the reader.
  const HandFile f;
  const GaussianCloud c = FromText(Json(f.Bin, f.Attributes, 2));
  float sh[12];
  for (int k = 0; k < 4; ++k)
  {
    for (int ch = 0; ch < 3; ++ch)
    {
      sh[3 * k + ch] = f.Sh[0][k][ch];
    }
  }
  const double d[3] = { 0.3, -0.5, 0.8124 };
  const double dTurned[3] = { -d[0], -d[1], d[2] };
  double a[3], b[3];
  ShColor<double>(sh, 1, d, a);
  ShColor<double>(&c.SH[0], 1, dTurned, b);
  for (int ch = 0; ch < 3; ++ch)
  {
    EXPECT_NEAR(a[ch], b[ch], 1e-7);
  }
}

/// Covariance (6 values) of Gaussian @p g in double.
std::array<double, 6> Cov(const GaussianCloud& c, std::size_t g)
{
  return GaussianCovariance<double>(&c.LogScales[3 * g], &c.Rotations[4 * g], 1.0);
}

TEST(GaussianGltf, NodeHierarchyMovesMeansCovariancesAndColour)
{
  const HandFile f;
  const GaussianCloud plain = FromText(Json(f.Bin, f.Attributes, 2));
  // Parent: translation and a quarter turn about y; child: uniform scale 2 and a translation.
  const std::string nodes = R"("nodes":[{"children":[1],"translation":[10,0,-1],)"
                            R"("rotation":[0,0.7071067811865476,0,0.7071067811865476]},)"
                            R"({"mesh":0,"scale":[2,2,2],"translation":[0,1,0]}])";
  const GaussianCloud moved = FromText(Json(f.Bin, f.Attributes, 2, nodes));
  // World matrix in glTF's frame: x' = Ry(90) (2x + (0,1,0)) + (10,0,-1); Ry(90): (x,y,z) ->
  // (z, y, -x). In the PLY's axes (half turn about z) the same map conjugated.
  for (std::size_t g = 0; g < 2; ++g)
  {
    const double x = -plain.Positions[3 * g], y = -plain.Positions[3 * g + 1],
                 z = plain.Positions[3 * g + 2];
    EXPECT_NEAR(moved.Positions[3 * g], -(2 * z + 10), 1e-5);
    EXPECT_NEAR(moved.Positions[3 * g + 1], -(2 * y + 1), 1e-5);
    EXPECT_NEAR(moved.Positions[3 * g + 2], -2 * x - 1, 1e-5);
    // Covariance: M Σ Mᵀ with M = F Ry(90) 2 F (F = diag(-1,-1,1)).
    const auto s = Cov(plain, g);
    const double S[3][3] = { { s[0], s[1], s[2] }, { s[1], s[3], s[4] }, { s[2], s[4], s[5] } };
    // F Ry F: (x,y,z) -> F Ry (-x,-y,z) = F (z, -y, x) = (-z, y, x).
    const double M[3][3] = { { 0, 0, -2 }, { 0, 2, 0 }, { 2, 0, 0 } };
    double E[3][3] = {};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            E[i][j] += M[i][a] * S[a][b] * M[j][b];
    const auto t = Cov(moved, g);
    const double T[3][3] = { { t[0], t[1], t[2] }, { t[1], t[3], t[4] }, { t[2], t[4], t[5] } };
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(T[i][j], E[i][j], 1e-5 * (1 + std::abs(E[i][j])));
    // Colour: the moved Gaussian seen along R d looks as the plain one along d.
    const double d[3] = { 0.48, 0.6, 0.64 };
    const double rd[3] = { -d[2], d[1], d[0] };
    double a[3], b[3];
    ShColor<double>(&plain.SH[12 * g], 1, d, a);
    ShColor<double>(&moved.SH[12 * g], 1, rd, b);
    for (int ch = 0; ch < 3; ++ch)
    {
      EXPECT_NEAR(a[ch], b[ch], 1e-6);
    }
  }
}

TEST(GaussianGltf, UnevenScaleKeepsTheExactCovarianceAndWarns)
{
  const HandFile f;
  const GaussianCloud plain = FromText(Json(f.Bin, f.Attributes, 2));
  const std::string nodes =
    R"("nodes":[{"mesh":0,"matrix":[1,0,0,0, 0.5,3,0,0, 0,0,0.25,0, 1,2,3,1]}])";
  GaussianReadReport report;
  const std::string json = Json(f.Bin, f.Attributes, 2, nodes);
  const GaussianCloud moved =
    ReadGltfFromMemory(json.data(), json.size(), "shear.gltf", {}, &report);
  ASSERT_EQ(report.Warnings.size(), 2u); // the shear, and the zero scale of Gaussian 1
  EXPECT_NE(report.Warnings[0].find("shears"), std::string::npos);
  // Column-major: glTF-frame M = [[1, 0.5, 0], [0, 3, 0], [0, 0, 0.25]]; in the PLY's axes
  // F M F = [[1, 0.5, 0], [0, 3, 0], [0, 0, 0.25]] (the off-diagonal x-y term keeps its sign).
  const double M[3][3] = { { 1, 0.5, 0 }, { 0, 3, 0 }, { 0, 0, 0.25 } };
  const auto s = Cov(plain, 0);
  const double S[3][3] = { { s[0], s[1], s[2] }, { s[1], s[3], s[4] }, { s[2], s[4], s[5] } };
  double E[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          E[i][j] += M[i][a] * S[a][b] * M[j][b];
  const auto t = Cov(moved, 0);
  const double T[3][3] = { { t[0], t[1], t[2] }, { t[1], t[3], t[4] }, { t[2], t[4], t[5] } };
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(T[i][j], E[i][j], 1e-5 * (1 + std::abs(E[i][j])));
  EXPECT_NEAR(moved.Positions[0], -(1 * -plain.Positions[0] + 0.5 * -plain.Positions[1] + 1), 1e-5);
}

TEST(GaussianGltf, MirrorsCyclesAndBrokenFilesAreRefusedWithTheirReason)
{
  const HandFile f;
  auto expectError = [](const std::string& json, const std::string& what)
  {
    try
    {
      FromText(json);
      ADD_FAILURE() << "no error for " << what;
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("test.gltf: ", 0), 0u) << e.what();
    }
  };
  expectError(
    Json(f.Bin, f.Attributes, 2, R"("nodes":[{"mesh":0,"scale":[-1,1,1]}])"), "determinant");
  expectError(Json(f.Bin, f.Attributes, 2, R"("nodes":[{"mesh":0,"children":[0]}])"), "cycle");
  // Two parents: along a chain each doubling would multiply the Gaussians exponentially.
  expectError(
    Json(f.Bin, f.Attributes, 2, R"("nodes":[{"children":[1,2]},{"children":[2]},{"mesh":0}])"),
    "two parents");
  std::string many = R"("nodes":[{"children":[)";
  for (int i = 1; i <= 17; ++i)
  {
    many += (i > 1 ? "," : "") + std::to_string(i);
  }
  many += "]}";
  for (int i = 1; i <= 17; ++i)
  {
    many += R"(,{"mesh":0})";
  }
  expectError(Json(f.Bin, f.Attributes, 2, many + "]"), "instanced by more than 16 nodes");
  std::string deep = R"("nodes":[)";
  for (int i = 0; i < 300; ++i)
  {
    deep += R"({"children":[)" + std::to_string(i + 1) + "]},";
  }
  expectError(Json(f.Bin, f.Attributes, 2, deep + R"({"mesh":0}])"), "deeper than 256");
  expectError(Json(f.Bin, f.Attributes, 3), "runs past the end of its buffer");
  std::string longer = Json(f.Bin, f.Attributes, 2);
  longer.replace(longer.find("\"count\":2"), 9, "\"count\":3");
  expectError(longer, "do not fit");
  expectError(Json(f.Bin, { "POSITION:VEC3" }, 2), "KHR_gaussian_splatting:ROTATION");
  auto partial = f.Attributes;
  partial.pop_back();
  expectError(Json(f.Bin, partial, 2), "partially defined");
  std::string noExt = Json(f.Bin, f.Attributes, 2);
  noExt.replace(noExt.find("\"extensions\":{\"KHR"), 13, "\"extensionz\":");
  expectError(noExt, "no node of the scene");
  expectError("{\"asset\":{\"version\":\"1.0\"}}", "glTF 2.0");
  expectError("{\"asset\":", "invalid glTF JSON");
  std::string external = Json(f.Bin, f.Attributes, 2);
  external.replace(external.find("data:"), 5, "x.bin#");
  expectError(external, "cannot reach");
  // A GLB whose header claims more than the file holds, or a chunk running past its end.
  const Bytes glb = WriteGltfToMemory(FromText(Json(f.Bin, f.Attributes, 2)), true);
  for (std::size_t cut : { std::size_t(3), std::size_t(15), glb.size() - 1 })
  {
    EXPECT_THROW(ReadGltfFromMemory(glb.data(), cut, "cut.glb"), std::runtime_error) << cut;
  }
  Bytes lying = glb;
  lying[12] = 0xff;
  lying[13] = 0xff;
  EXPECT_THROW(ReadGltfFromMemory(lying.data(), lying.size(), "lying.glb"), std::runtime_error);
}

GaussianCloud RandomCloud(std::size_t n, int degree, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal;
  std::uniform_real_distribution<float> u(-3, 3);
  GaussianCloud c;
  c.Resize(n, degree);
  for (auto& v : c.Positions)
    v = 10 * u(rng);
  for (auto& v : c.LogScales)
    v = u(rng) - 2;
  for (auto& v : c.Rotations)
    v = normal(rng);
  for (auto& v : c.OpacityLogits)
    v = 2 * u(rng);
  for (auto& v : c.SH)
    v = u(rng) / 3;
  ExtraProperty score{ "score", ScalarType::Float32, {} };
  ExtraProperty flag{ "flag", ScalarType::UInt8, {} };
  for (std::size_t i = 0; i < n; ++i)
  {
    const float s = u(rng);
    score.Bytes.insert(score.Bytes.end(),
      reinterpret_cast<const unsigned char*>(&s),
      reinterpret_cast<const unsigned char*>(&s) + 4);
    flag.Bytes.push_back(static_cast<unsigned char>(i % 7));
  }
  c.Extra = { score, flag };
  return c;
}

TEST(GaussianGltf, WriterRoundTripIsExactInWhatItStoresExactly)
{
  const GaussianCloud src = RandomCloud(500, 3, 34);
  for (const bool binary : { true, false })
  {
    GltfWriteReport report;
    const Bytes bytes = WriteGltfToMemory(src, binary, {}, &report);
    EXPECT_EQ(report.Written, 500u);
    EXPECT_EQ(report.LeftOut, 0u);
    EXPECT_EQ(bytes[0] == 'g', binary);
    const GaussianCloud a = ReadGltfFromMemory(bytes.data(), bytes.size(), "a");
    ASSERT_EQ(a.Count, 500u);
    ASSERT_EQ(a.ShDegree, 3);
    EXPECT_EQ(a.Positions, src.Positions);
    EXPECT_EQ(a.SH, src.SH);
    ASSERT_EQ(a.Extra.size(), 2u);
    EXPECT_EQ(a.Extra[0].Name, "score");
    EXPECT_EQ(a.Extra[0].Bytes, src.Extra[0].Bytes);
    EXPECT_EQ(a.Extra[1].Type, ScalarType::UInt8);
    EXPECT_EQ(a.Extra[1].Bytes, src.Extra[1].Bytes);
    for (std::size_t i = 0; i < 3 * a.Count; ++i)
    {
      EXPECT_NEAR(a.LogScales[i], src.LogScales[i], 1e-6);
    }
    // The reported errors are what reading back shows: positions and SH exact.
    double maxScale = 0;
    for (std::size_t i = 0; i < 3 * a.Count; ++i)
    {
      maxScale = std::max(maxScale, std::abs(double(a.LogScales[i]) - src.LogScales[i]));
    }
    ASSERT_GE(report.Errors.size(), 5u);
    EXPECT_EQ(report.Errors[0].Attribute, "position");
    EXPECT_EQ(report.Errors[0].Max, 0.0);
    EXPECT_EQ(report.Errors[1].Max, maxScale);
    EXPECT_EQ(report.Errors[4].Max, 0.0);
    EXPECT_LT(report.Errors[2].Max, 1e-3); // rotation, degrees
    // Rotations are stored normalised: a second write stores and reads back the same bits.
    const Bytes again = WriteGltfToMemory(a, binary);
    const GaussianCloud b = ReadGltfFromMemory(again.data(), again.size(), "b");
    EXPECT_EQ(b.Rotations, a.Rotations);
    EXPECT_EQ(b.Positions, a.Positions);
    EXPECT_EQ(b.SH, a.SH);
  }
}

TEST(GaussianGltf, WriterLeavesOutWhatTheReferenceCannotDrawAndCutsSh)
{
  GaussianCloud src = RandomCloud(10, 3, 7);
  src.Positions[3] = std::numeric_limits<float>::quiet_NaN();
  src.OpacityLogits[4] = std::numeric_limits<float>::infinity();
  std::fill_n(&src.Rotations[20], 4, 0.0f);
  GltfWriteOptions options;
  options.MaxShDegree = 1;
  options.KeepExtras = false;
  GltfWriteReport report;
  const Bytes bytes = WriteGltfToMemory(src, true, options, &report);
  EXPECT_EQ(report.Written, 9u);
  EXPECT_EQ(report.LeftOut, 1u);
  const GaussianCloud a = ReadGltfFromMemory(bytes.data(), bytes.size(), "a");
  EXPECT_EQ(a.Count, 9u);
  EXPECT_EQ(a.ShDegree, 1);
  EXPECT_TRUE(a.Extra.empty());
  EXPECT_TRUE(std::isinf(a.OpacityLogits[3]) && a.OpacityLogits[3] > 0); // source 4
  EXPECT_EQ(a.Rotations[16], 1.0f);                                      // source 5: identity
  EXPECT_NE(DescribeQuantisation(report).find("1 left out"), std::string::npos);
  GaussianCloud none = RandomCloud(1, 0, 1);
  none.Positions[0] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(WriteGltfToMemory(none, true), std::runtime_error);
}

TEST(GaussianGltf, SpzPayloadReadsAsTheSpzReaderReadsIt)
{
  const GaussianCloud src = RandomCloud(64, 2, 3);
  const Bytes spz = WriteSpzToMemory(src);
  // The draft's layout: the SPZ blob in a bufferView named by the nested extension; the
  // attributes are placeholders without bufferViews.
  const std::string json =
    R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_gaussian_splatting","KHR_gaussian_splatting_compression_spz_2"],)"
    R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"mode":0,)"
    R"("attributes":{"POSITION":0},"extensions":{"KHR_gaussian_splatting":{"kernel":"ellipse",)"
    R"("colorSpace":"srgb_rec709_display","extensions":{"KHR_gaussian_splatting_compression_spz_2":{"bufferView":0}}}}}]}],)"
    R"("accessors":[{"componentType":5126,"count":64,"type":"VEC3"}],)"
    R"("bufferViews":[{"buffer":0,"byteLength":)" +
    std::to_string(spz.size()) + R"(}],"buffers":[{"byteLength":)" + std::to_string(spz.size()) +
    R"(,"uri":"data:application/octet-stream;base64,)" +
    detail::EncodeBase64(spz.data(), spz.size()) + "\"}]}";
  const GaussianCloud viaGltf = FromText(json);
  const GaussianCloud direct = ReadSpzFromMemory(spz.data(), spz.size(), "direct.spz");
  ASSERT_EQ(viaGltf.Count, direct.Count);
  EXPECT_EQ(viaGltf.Positions, direct.Positions);
  EXPECT_EQ(viaGltf.LogScales, direct.LogScales);
  EXPECT_EQ(viaGltf.Rotations, direct.Rotations);
  EXPECT_EQ(viaGltf.SH, direct.SH);
  EXPECT_EQ(viaGltf.OpacityLogits, direct.OpacityLogits);
}

TEST(GaussianGltf, SceneDispatcherReadsGlbAndGltfWithAnExternalBuffer)
{
  TempDir dir;
  const HandFile f;
  const GaussianCloud src = FromText(Json(f.Bin, f.Attributes, 2));
  WriteGltf(dir / "scene.glb", src);
  GaussianReadReport report;
  const GaussianCloud a = ReadGaussianScene(dir / "scene.glb", {}, &report);
  EXPECT_EQ(report.Format, "gltf");
  EXPECT_EQ(a.Positions, src.Positions);
  // JSON with the buffer in a file beside it, under a name that needs percent-decoding.
  std::string json = Json(f.Bin, f.Attributes, 2);
  const auto uri = json.find("data:");
  json.replace(uri, json.find('"', uri) - uri, "my%20splats.bin");
  WriteFile(dir / "my splats.bin", f.Bin);
  WriteFile(dir / "scene.gltf", json);
  EXPECT_TRUE(IsGltfFile(dir / "scene.gltf"));
  EXPECT_EQ(ReadGaussianScene(dir / "scene.gltf").SH, src.SH);
  // A glTF under another name is still recognised by its content.
  WriteGltf(dir / "copy.gltf", src);
  std::rename((dir / "copy.gltf").c_str(), (dir / "copy.json").c_str());
  EXPECT_EQ(ReadGaussianScene(dir / "copy.json").Rotations, src.Rotations);
  EXPECT_FALSE(IsGltfFile(dir / "my splats.bin"));
}

} // namespace
} // namespace vis4gs
