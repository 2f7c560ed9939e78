// SPDX-License-Identifier: BSD-3-Clause
// The trainer: Adam and the schedules against hand-computed references, initialisation,
// adaptive density control with its genealogy bookkeeping on a hand-built case, short
// training runs (loss decreases, the log replays to the final ids), determinism and
// interruption. Every run here is a few hundred iterations on 32x32 images (seconds).
#include "Adam.h"
#include "GaussianMath.h"
#include "Loss.h"
#include "Rasterizer.h"
#include "Trainer.h"
#include "TrainingData.h"
#include "TrainingLogReader.h"
#include "TrainingLogWriter.h"

#include "SyntheticScene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <unistd.h>

using namespace vis4gs;

namespace
{

const char* TinyScene = R"({
  "name": "tiny", "seed": 5, "width": 32, "height": 32, "background": [0, 0, 0],
  "objects": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.45, "gaussians": 1500,
     "texture": {"pattern": "checker", "colors": [[0.9, 0.3, 0.1], [0.2, 0.4, 0.9]], "frequency": [8, 4]}},
    {"type": "box", "center": [0, 0, -0.6], "size": [1.6, 1.6, 0.1], "gaussians": 1000,
     "texture": {"pattern": "stripes", "colors": [[0.9, 0.9, 0.9], [0.1, 0.1, 0.1]], "frequency": [6, 1]}}
  ],
  "cameras": [
    {"path": "orbit", "count": 10, "radius": 2.5, "elevation_deg": 30},
    {"path": "orbit", "count": 2, "radius": 2.5, "elevation_deg": 40, "start_deg": 20, "end_deg": 200, "split": "test"}
  ],
  "initial_points": {"count": 150, "position_noise": 0.02, "outlier_fraction": 0.05,
                     "outlier_box": [[-1, -1, -1], [1, 1, 1]]}
})";

TrainingData TinyData()
{
  const SyntheticScene s = MakeSyntheticScene(TinyScene, "tiny.json");
  TrainingData d;
  d.Name = s.Name;
  d.Cameras = s.Cameras;
  d.Images = s.Images;
  d.PointPositions = s.PointPositions;
  d.PointColors = s.PointColors;
  d.Background = s.Background;
  return d;
}

// A scaled schedule with intervals that suit a few hundred iterations (ScaleSchedule alone
// would densify every iteration below 1500 iterations).
TrainerOptions ShortRun(int iterations)
{
  TrainerOptions o;
  o.ScaleSchedule(iterations);
  o.DensificationInterval = 10;
  o.DensifyFromIter = 20;
  o.DensifyUntilIter = iterations * 5 / 8;
  o.OpacityResetInterval = iterations / 4 + 5;
  o.ShIncreaseInterval = iterations / 8;
  o.DensifyGradThreshold = 0.002; // 32x32 images: keep the growth (and the test time) small
  o.Seed = 11;
  o.Threads = 1; // OpenMP threads spin-wait: keep the tests fast on a loaded machine
  o.SnapshotInterval = iterations / 4;
  o.MetricsInterval = iterations / 4;
  return o;
}

std::string TempPath(const std::string& tag)
{
  return "/tmp/vis4gs_trainer_" + std::to_string(::getpid()) + "_" + tag + ".h5";
}

} // namespace

//------------------------------------------------------------------------------
TEST(Adam, MatchesPyTorchRecurrence)
{
  const std::size_t n = 7;
  std::vector<float> p(n), g(n);
  std::vector<double> pd(n), m(n, 0), v(n, 0);
  std::mt19937 rng(1);
  std::normal_distribution<float> nd(0, 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    p[i] = nd(rng);
    pd[i] = p[i];
  }
  AdamState st;
  st.Reset(n);
  for (int step = 1; step <= 20; ++step)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      g[i] = step % 5 == 0 && i == 3 ? 0.0f : nd(rng); // zero gradients still move (dense)
    }
    // period 7 with the first 2 values at another rate (the SH layout trick)
    AdamStep(st, p.data(), g.data(), n, 1e-2, 1, 7, 2, 5e-2);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double lr = i < 2 ? 5e-2 : 1e-2;
      m[i] = 0.9 * m[i] + 0.1 * g[i];
      v[i] = 0.999 * v[i] + 0.001 * double(g[i]) * g[i];
      const double mh = m[i] / (1 - std::pow(0.9, step));
      const double denom = std::sqrt(v[i]) / std::sqrt(1 - std::pow(0.999, step)) + 1e-15;
      pd[i] -= lr * mh / denom;
    }
  }
  EXPECT_EQ(st.Step, 20);
  for (std::size_t i = 0; i < n; ++i)
  {
    EXPECT_NEAR(p[i], pd[i], 2e-5 * (1 + std::abs(pd[i]))) << i;
  }
  // First step moves every value with a non-zero gradient by exactly lr (m/sqrt(v) = sign).
  AdamState s2;
  s2.Reset(2);
  std::vector<float> q = { 1.0f, 1.0f }, gq = { 3.0f, -0.001f };
  AdamStep(s2, q.data(), gq.data(), 2, 0.1);
  EXPECT_NEAR(q[0], 0.9f, 1e-6);
  EXPECT_NEAR(q[1], 1.1f, 1e-6);
}

TEST(TrainerOptions, ScaleScheduleIsProportional)
{
  TrainerOptions o;
  o.ScaleSchedule(3000);
  EXPECT_EQ(o.Iterations, 3000);
  EXPECT_EQ(o.PositionLrMaxSteps, 3000);
  EXPECT_EQ(o.DensifyFromIter, 50);
  EXPECT_EQ(o.DensifyUntilIter, 1500);
  EXPECT_EQ(o.DensificationInterval, 10);
  EXPECT_EQ(o.OpacityResetInterval, 300);
  EXPECT_EQ(o.ShIncreaseInterval, 100);
  o.ScaleSchedule(30000);
  EXPECT_EQ(o.DensificationInterval, 100);
  EXPECT_EQ(o.OpacityResetInterval, 3000);
  o.ScaleSchedule(10);
  EXPECT_EQ(o.DensificationInterval, 1); // never below 1
  EXPECT_THROW(o.ScaleSchedule(0), std::invalid_argument);
}

TEST(Trainer, ThreeNearestNeighboursMatchBruteForce)
{
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-1, 1);
  for (int variant = 0; variant < 3; ++variant)
  {
    std::vector<float> pts;
    for (int i = 0; i < 700; ++i)
    {
      pts.push_back(u(rng) * (variant == 1 ? 100.f : 1.f));
      pts.push_back(u(rng));
      pts.push_back(variant == 2 ? 0.5f : u(rng) * u(rng)); // planar, then clustered
    }
    // Duplicates count with distance 0.
    for (int k = 0; k < 3; ++k)
    {
      pts.push_back(pts[k]);
    }
    const auto d = Trainer::MeanSquaredDistance3NN(pts);
    const std::size_t n = pts.size() / 3;
    for (std::size_t i = 0; i < n; i += 13)
    {
      std::vector<double> all;
      for (std::size_t j = 0; j < n; ++j)
      {
        if (j != i)
        {
          double s = 0;
          for (int k = 0; k < 3; ++k)
          {
            const double t = double(pts[3 * i + k]) - pts[3 * j + k];
            s += t * t;
          }
          all.push_back(s);
        }
      }
      std::partial_sort(all.begin(), all.begin() + 3, all.end());
      EXPECT_NEAR(d[i], (all[0] + all[1] + all[2]) / 3, 1e-6 * (all[2] + 1e-12))
        << variant << " " << i;
    }
    EXPECT_LE(d[0], d[1] + 1e30f);
  }
  EXPECT_EQ(Trainer::MeanSquaredDistance3NN({ 1, 2, 3 }), std::vector<float>{ 0.0f });
  const auto two = Trainer::MeanSquaredDistance3NN({ 0, 0, 0, 0, 0, 2 });
  EXPECT_FLOAT_EQ(two[0], 4.0f); // one neighbour only: its squared distance
}

TEST(Trainer, InitialisationFromPoints)
{
  const std::vector<float> pos = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0 };
  const std::vector<float> col = {
    0.5f, 1, 0, 0.2f, 0.2f, 0.2f, 0, 0, 0, 1, 1, 1, 0.5f, 0.5f, 0.5f
  };
  const GaussianCloud c = Trainer::InitializeFromPoints(pos, col, 3);
  ASSERT_EQ(c.Count, 5u);
  EXPECT_EQ(c.ShDegree, 3);
  EXPECT_EQ(c.Ids, (std::vector<std::int64_t>{ 0, 1, 2, 3, 4 }));
  EXPECT_NEAR(Sigmoid(c.OpacityLogits[2]), 0.1f, 1e-7);
  EXPECT_FLOAT_EQ(c.Rotations[4], 1.0f);
  EXPECT_FLOAT_EQ(c.Rotations[5], 0.0f);
  EXPECT_NEAR(0.5 + sh::C0 * c.SH[1], 1.0, 1e-6); // DC of point 0, green
  EXPECT_EQ(c.SH[3], 0.0f);                       // SH rest is zero
  // Point 0 (duplicated by point 4): neighbours at 0, 1, 1 -> mean 2/3.
  EXPECT_NEAR(std::exp(2 * c.LogScales[0]), 2.0 / 3, 1e-6);
  // Point 1: neighbours 0 (x2) at 1 and points 2, 3 at sqrt(2) -> (1+1+2)/3.
  EXPECT_NEAR(std::exp(2 * c.LogScales[3]), 4.0 / 3, 1e-6);
  EXPECT_EQ(c.LogScales[3], c.LogScales[5]);
}

TEST(Trainer, DensifyAndPruneFollowsTheReferenceBookkeeping)
{
  TrainingData d = TinyData();
  d.PointPositions.resize(18);
  d.PointColors.resize(18);
  TrainerOptions o = ShortRun(300);
  o.DensifyGradThreshold = 0.0002;
  Trainer t(d, o);
  t.Step(); // non-zero Adam moments
  const double E = t.GetSceneExtent();
  GaussianCloud& c = t.GetMutableCloud();
  ASSERT_EQ(c.Count, 6u);
  const float small = static_cast<float>(std::log(0.005 * E)),
              large = static_cast<float>(std::log(0.05 * E));
  const float ls[6] = { small, small, large, large, small, large };
  for (int i = 0; i < 6; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.LogScales[3 * i + k] = ls[i] - 0.1f * k; // max scale on axis 0
      c.Positions[3 * i + k] = 0.1f * i;
    }
    c.OpacityLogits[i] = i == 4 ? Logit(0.001f) : 0.0f;
  }
  const std::vector<float> before = t.GetPositionMoments();
  // Mean gradients (accum / denom): 0 high, 1 low, 2 high, 3 low, 4 high (low opacity),
  // 5 never seen (0/0 -> 0).
  t.SetGradientStatistics(
    { 0.003f, 0.0001f, 0.0009f, 0.00001f, 0.0008f, 0.0f }, { 10, 10, 3, 2, 2, 0 });
  t.DensifyAndPruneAt(20);
  const EventTable& ev = t.GetEvents();
  ASSERT_EQ(ev.Size(), 6u);
  auto expect = [&](std::size_t r, EventKind k, std::int64_t p, std::int64_t ch)
  {
    const TrainingEvent e = ev.Get(r);
    EXPECT_EQ(e.Iteration, 20);
    EXPECT_EQ(e.Kind, k) << r;
    EXPECT_EQ(e.Parent, p) << r;
    EXPECT_EQ(e.Child, ch) << r;
  };
  expect(0, EventKind::Clone, 0, 6);
  expect(1, EventKind::Clone, 4, 7);
  expect(2, EventKind::Split, 2, 8);
  expect(3, EventKind::Split, 2, 9);
  expect(4, EventKind::Prune, 4, -1); // the low-opacity parent and its fresh clone
  expect(5, EventKind::Prune, 7, -1);
  EXPECT_EQ(c.Ids, (std::vector<std::int64_t>{ 0, 1, 3, 5, 6, 8, 9 }));
  // The clone is an exact copy; split children have log-scales ln(s/1.6), same rotation.
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_EQ(c.Positions[3 * 4 + k], c.Positions[k]);
    EXPECT_EQ(c.LogScales[3 * 4 + k], c.LogScales[k]);
    for (int child : { 5, 6 })
    {
      EXPECT_NEAR(c.LogScales[3 * child + k], ls[2] - 0.1f * k - std::log(1.6f), 1e-5);
      EXPECT_LT(std::abs(c.Positions[3 * child + k] - 0.2f), 6 * std::exp(ls[2]));
    }
  }
  EXPECT_NE(c.Positions[15], c.Positions[18]); // two independent samples
  // Adam: new rows have zero moments, survivors keep theirs.
  const std::vector<float>& after = t.GetPositionMoments();
  ASSERT_EQ(after.size(), 21u);
  const int survivors[4] = { 0, 1, 3, 5 };
  for (int r = 0; r < 4; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(after[3 * r + k], before[3 * survivors[r] + k]);
    }
  }
  for (std::size_t k = 12; k < 21; ++k)
  {
    EXPECT_EQ(after[k], 0.0f);
  }
  // Accumulators are reset.
  for (float v : t.GetGradientAccumulator())
  {
    EXPECT_EQ(v, 0.0f);
  }
  EXPECT_EQ(t.GetDenominator().size(), 7u);

  // Past the opacity reset interval the world-size prune (max scale > 0.1 E) is active.
  const float giant = static_cast<float>(std::log(0.2 * E));
  c.LogScales[0] = giant;
  t.SetGradientStatistics(std::vector<float>(7, 0.0f), std::vector<float>(7, 1.0f));
  t.DensifyAndPruneAt(o.OpacityResetInterval - 10);
  EXPECT_EQ(t.GetCloud().Count, 7u);
  t.DensifyAndPruneAt(o.OpacityResetInterval + 10);
  EXPECT_EQ(t.GetCloud().Count, 6u);
  EXPECT_EQ(t.GetEvents().Get(6).Kind, EventKind::Prune);
  EXPECT_EQ(t.GetEvents().Get(6).Parent, 0);
}

TEST(Trainer, ShortRunReducesLossAndLogReplaysToFinalIds)
{
  const std::string path = TempPath("run");
  TrainerOptions o = ShortRun(200);
  o.EmbedImages = true;
  o.MetricsMaxTrainViews = 4;
  o.ProgressInterval = 50;
  {
    Trainer t(TinyData(), o);
    TrainingLogWriterOptions wo;
    wo.Iterations = o.Iterations;
    wo.ShDegree = o.ShDegree;
    wo.Scene = "tiny";
    wo.Producer = "vis4gs-train-test";
    TrainingLogWriter log(path, wo);
    int calls = 0;
    EXPECT_EQ(t.Run(&log,
                nullptr,
                [&](const TrainerProgress& p)
                {
                  ++calls;
                  EXPECT_GT(p.NumGaussians, 0u);
                }),
      200);
    EXPECT_EQ(calls, 4);
    EXPECT_EQ(t.GetActiveShDegree(), 3);
    EXPECT_GT(t.GetEvents().Size(), 0u);
  }
  TrainingLogReader r(path);
  EXPECT_EQ(r.GetHeader().Iterations, 200);
  EXPECT_EQ(r.GetSnapshotIterations(), (std::vector<int>{ 0, 50, 100, 150, 200 }));
  const MetricsTable m = r.ReadMetrics(false);
  ASSERT_EQ(m.Size(), 5u);
  EXPECT_GT(m.Psnr.back(), m.Psnr.front() + 3.0);
  EXPECT_LT(m.Loss.back(), m.Loss.front());
  EXPECT_TRUE(std::isnan(m.Lpips.back()));
  EXPECT_EQ(r.ReadMetrics(true).Size(), 5u);
  EXPECT_EQ(r.GetImageNames().size(), 12u);
  // Replaying the events from the initial ids gives every snapshot's ids.
  const EventTable ev = r.ReadEvents();
  std::set<std::int64_t> alive;
  for (std::int64_t id : r.ReadSnapshot(0).Ids)
  {
    alive.insert(id);
  }
  std::size_t row = 0;
  std::int64_t lastNew = static_cast<std::int64_t>(alive.size()) - 1;
  for (int it : r.GetSnapshotIterations())
  {
    for (; row < ev.Size() && ev.Iteration[row] <= it; ++row)
    {
      const TrainingEvent e = ev.Get(row);
      ASSERT_TRUE(alive.count(e.Parent)) << "row " << row;
      if (e.Kind == EventKind::Prune)
      {
        alive.erase(e.Parent);
        continue;
      }
      EXPECT_EQ(e.Child, lastNew + 1); // ids handed out in order, never reused
      lastNew = e.Child;
      alive.insert(e.Child);
    }
    // A split ends its parent (no prune row for it).
    std::set<std::int64_t> ids;
    for (std::int64_t id : r.ReadSnapshot(it).Ids)
    {
      ids.insert(id);
    }
    std::set<std::int64_t> expected = alive;
    for (std::size_t k = 0; k < row; ++k)
    {
      if (ev.Kind[k] == 2)
      {
        expected.erase(ev.Parent[k]);
      }
    }
    EXPECT_EQ(ids, expected) << "snapshot " << it;
  }
  EXPECT_EQ(row, ev.Size());
  const GaussianCloud last = r.ReadSnapshot(200, SnapshotReadOptions{ SnapshotAll, -1 });
  EXPECT_EQ(last.ShDegree, 3);
  EXPECT_NE(last.FindExtra("grad_accum"), nullptr);
  std::remove(path.c_str());
}

// The blocked, vectorised AdamStep gives exactly the per-element recurrence (the previous
// straightforward loop), with and without the SH two-rate layout, on 1 and 2 threads.
TEST(Adam, VectorisedStepIsBitIdenticalToThePlainLoop)
{
  const std::size_t n = 48 * 2101 + 5; // above the parallel threshold, partial last row
  std::mt19937 rng(3);
  std::normal_distribution<float> nd(0, 1);
  std::vector<float> p0(n), g(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    p0[i] = nd(rng);
    g[i] = i % 11 == 0 ? 0.0f : nd(rng) * 1e-3f;
  }
  for (std::size_t period : { std::size_t(0), std::size_t(48) })
  {
    for (int threads : { 1, 2 })
    {
      std::vector<float> p = p0, q = p0;
      AdamState st;
      st.Reset(n);
      std::vector<float> m(n, 0.0f), v(n, 0.0f);
      for (int step = 1; step <= 3; ++step)
      {
        AdamStep(st, p.data(), g.data(), n, 1.6e-4, threads, period, 3, 2.5e-3);
        const double bc1 = 1.0 - std::pow(0.9, step), bc2 = 1.0 - std::pow(0.999, step);
        const float sz = static_cast<float>(1.6e-4 / bc1), sz1 = static_cast<float>(2.5e-3 / bc1);
        const float bc2s = static_cast<float>(std::sqrt(bc2));
        for (std::size_t i = 0; i < n; ++i)
        {
          m[i] = m[i] + (g[i] - m[i]) * static_cast<float>(1.0 - 0.9);
          v[i] = v[i] * static_cast<float>(0.999) + static_cast<float>(1.0 - 0.999) * g[i] * g[i];
          const float denom = std::sqrt(v[i]) / bc2s + static_cast<float>(1e-15);
          const float s = (period > 0 && i % period < 3) ? sz1 : sz;
          q[i] = q[i] - s * (m[i] / denom);
        }
      }
      EXPECT_EQ(p, q) << "period " << period << ", " << threads << " threads";
      EXPECT_EQ(st.M, m);
      EXPECT_EQ(st.V, v);
    }
  }
}

TEST(Trainer, SameSeedAndThreadsGiveTheSameRun)
{
  TrainerOptions o = ShortRun(120);
  o.Threads = 2;
  Trainer a(TinyData(), o), b(TinyData(), o);
  a.Run(nullptr);
  b.Run(nullptr);
  EXPECT_EQ(a.GetCloud().Positions, b.GetCloud().Positions);
  EXPECT_EQ(a.GetCloud().SH, b.GetCloud().SH);
  EXPECT_EQ(a.GetCloud().Ids, b.GetCloud().Ids);
  EXPECT_EQ(a.GetEvents().Parent, b.GetEvents().Parent);
  // The thread count does not change the result either (fixed-order reductions).
  o.Threads = 1;
  Trainer c(TinyData(), o);
  c.Run(nullptr);
  EXPECT_EQ(a.GetCloud().Positions, c.GetCloud().Positions);
  // Nor does the instruction set of the 16-lane compositing loops (baseline x86-64 here).
  o.Threads = 2;
  o.KernelIsa = 1;
  Trainer d(TinyData(), o);
  d.Run(nullptr);
  EXPECT_EQ(a.GetCloud().Positions, d.GetCloud().Positions);
  EXPECT_EQ(a.GetCloud().SH, d.GetCloud().SH);
  o.KernelIsa = 0;
  o.Seed = 12;
  Trainer e(TinyData(), o);
  e.Run(nullptr);
  EXPECT_NE(a.GetCloud().Positions, e.GetCloud().Positions);
}

// Evaluate() keeps its rendering buffers, the cloud's preparation within a call and the
// targets' SSIM maps between calls: its rows equal, bit for bit, the straightforward pass
// (an allocating Rasterize(), L1Loss(), Ssim(), Psnr() per view), also after the cloud changed.
TEST(Trainer, EvaluateEqualsAPlainMetricsPass)
{
  TrainerOptions o = ShortRun(60);
  o.Threads = 2;
  Trainer t(TinyData(), o);
  auto plain = [&t](bool test)
  {
    RasterSettings settings;
    settings.Background = t.GetData().Background;
    settings.ShDegree = t.GetActiveShDegree();
    settings.Threads = 2;
    double l1 = 0, ssim = 0, psnr = 0;
    int views = 0;
    for (std::size_t v = 0; v < t.GetData().Cameras.size(); ++v)
    {
      const Camera& cam = t.GetData().Cameras[v];
      if ((cam.Split == CameraSplit::Test) != test)
      {
        continue;
      }
      RasterImage<float> img = Rasterize<float>(t.GetCloud(), cam, settings);
      for (float& x : img.Color)
      {
        x = std::min(1.0f, std::max(0.0f, x));
      }
      const float* gt = t.GetData().Images[v].data();
      l1 += L1Loss(img.Color.data(), gt, img.Color.size());
      ssim += Ssim(img.Color.data(), gt, cam.Width, cam.Height, 2);
      psnr += Psnr(img.Color.data(), gt, img.Color.size());
      ++views;
    }
    return std::array<double, 3>{ l1 / views, ssim / views, psnr / views };
  };
  for (int round = 0; round < 3; ++round)
  {
    for (bool test : { false, true })
    {
      const MetricsRow row = t.Evaluate(test);
      const std::array<double, 3> expected = plain(test);
      EXPECT_EQ(row.L1, expected[0]) << "round " << round << " test " << test;
      EXPECT_EQ(row.Ssim, expected[1]) << "round " << round << " test " << test;
      EXPECT_EQ(row.Psnr, expected[2]) << "round " << round << " test " << test;
    }
    for (int k = 0; k < 25; ++k) // densifies at 21 (new rows) and trains: a new cloud
    {
      t.Step();
    }
  }
  EXPECT_GT(t.GetCloud().Count, 150u);
}

// A fine-tune from a given cloud (vis4gs repair, issue 20): the pruned ids are logged first, at
// the start iteration, after a snapshot of the start cloud; positions with a zero learning rate
// stay exactly where they were; iterations continue from the start.
TEST(Trainer, FineTuneFromACloudPrunesFirstAndKeepsFixedPositions)
{
  TrainerOptions o = ShortRun(60);
  Trainer first(TinyData(), o);
  first.Run(nullptr);
  const GaussianCloud start = first.GetCloud();
  ASSERT_GT(start.Count, 4u);
  const std::vector<std::int64_t> prunes = { start.Ids[1], start.Ids[3] };
  TrainerOptions f = o;
  f.Iterations = 60 + 20;
  f.DensifyUntilIter = 0;
  f.PositionLrInit = f.PositionLrFinal = 0;
  f.SnapshotInterval = 20;
  f.MetricsInterval = 20;
  const std::string path = TempPath("finetune");
  {
    Trainer t(TinyData(), f, start, 60, prunes);
    EXPECT_EQ(t.GetIteration(), 60);
    EXPECT_EQ(t.GetActiveShDegree(), f.ShDegree);
    TrainingLogWriterOptions wo;
    wo.Iterations = f.Iterations;
    wo.ShDegree = f.ShDegree;
    TrainingLogWriter log(path, wo);
    EXPECT_EQ(t.Run(&log), 80);
    const GaussianCloud& c = t.GetCloud();
    ASSERT_EQ(c.Count, start.Count - 2);
    for (std::size_t i = 0, j = 0; i < start.Count; ++i)
    {
      if (i == 1 || i == 3)
      {
        continue;
      }
      EXPECT_EQ(c.Ids[j], start.Ids[i]);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(c.Positions[3 * j + k], start.Positions[3 * i + k]) << "row " << i;
      }
      ++j;
    }
    EXPECT_NE(c.OpacityLogits,
      std::vector<float>(
        start.OpacityLogits.begin(), start.OpacityLogits.begin() + static_cast<long>(c.Count)));
  }
  TrainingLogReader r(path);
  EXPECT_EQ(r.GetSnapshotIterations(), (std::vector<int>{ 60, 80 }));
  EXPECT_EQ(r.ReadSnapshot(60).Ids, start.Ids);
  const EventTable e = r.ReadEvents();
  ASSERT_EQ(e.Size(), 2u);
  EXPECT_EQ(e.Iteration, (std::vector<std::int32_t>{ 60, 60 }));
  EXPECT_EQ(e.Parent, prunes);
  EXPECT_EQ(r.ReadMetrics(false).Iteration.front(), 60);
  // A prune id the cloud lacks is refused.
  EXPECT_THROW(Trainer(TinyData(), f, start, 60, { 1 << 30 }), std::invalid_argument);
  std::remove(path.c_str());
}

TEST(Trainer, OptimizerSkipsDensificationAndResetIterations)
{
  TrainerOptions o = ShortRun(150);
  o.DensificationInterval = 5;
  o.OpacityResetInterval = 32;
  o.DensifyFromIter = 10;
  o.DensifyUntilIter = 100;
  o.DensifyGradThreshold = 0.01;
  Trainer t(TinyData(), o);
  t.Run(nullptr);
  int densify = 0, resetOnly = 0;
  for (int it = 1; it < 150; ++it)
  {
    const bool d = it < 100 && it > 10 && it % 5 == 0;
    const bool r = it < 100 && it % 32 == 0;
    densify += d;
    resetOnly += r && !d;
  }
  const auto steps = t.GetOptimizerSteps();
  EXPECT_EQ(steps[0], 149 - densify); // no step at the last iteration
  EXPECT_EQ(steps[1], steps[0]);
  EXPECT_EQ(steps[2], steps[0] - resetOnly);
  EXPECT_EQ(steps[3], steps[0]);
  EXPECT_EQ(steps[4], steps[0]);
}

TEST(Trainer, InterruptLeavesAValidLog)
{
  const std::string path = TempPath("stop");
  TrainerOptions o = ShortRun(200);
  std::atomic<bool> stop{ false };
  o.ProgressInterval = 10;
  {
    Trainer t(TinyData(), o);
    TrainingLogWriterOptions wo;
    wo.Iterations = o.Iterations;
    TrainingLogWriter log(path, wo);
    const int last = t.Run(&log,
      &stop,
      [&](const TrainerProgress& p)
      {
        if (p.Iteration == 70)
        {
          stop = true; // what the SIGINT handler does
        }
      });
    EXPECT_EQ(last, 70);
  }
  TrainingLogReader r(path);
  EXPECT_EQ(r.GetSnapshotIterations(), (std::vector<int>{ 0, 50, 70 }));
  EXPECT_EQ(r.ReadMetrics(false).Iteration.back(), 70);
  EXPECT_EQ(r.GetHeader().Iterations, 200);
  std::remove(path.c_str());
}

TEST(Trainer, RejectsUnusableData)
{
  TrainingData d = TinyData();
  TrainingData noTrain = d;
  for (Camera& c : noTrain.Cameras)
  {
    c.Split = CameraSplit::Test;
  }
  EXPECT_THROW(Trainer(noTrain, ShortRun(10)), std::invalid_argument);
  TrainingData badImage = d;
  badImage.Images[3].resize(10);
  try
  {
    Trainer t(badImage, ShortRun(10));
    FAIL() << "no error";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find(d.Cameras[3].Name), std::string::npos);
  }
  TrainingData noPoints = d;
  noPoints.PointPositions.clear();
  noPoints.PointColors.clear();
  EXPECT_THROW(Trainer(noPoints, ShortRun(10)), std::invalid_argument);
  EXPECT_THROW(LoadTrainingData("/nonexistent/folder"), std::runtime_error);
}

// The committed demo log (Data/Demo/README.md): complete, and its events replay exactly to
// the ids of its last snapshot.
TEST(Trainer, EmbeddedDemoLogIsConsistent)
{
  const std::string path = std::string(VIS4GS_SOURCE_DIR) + "/Data/Demo/vis4gs-demo.h5";
  TrainingLogReader r(path);
  EXPECT_TRUE(r.GetLacks().empty());
  EXPECT_EQ(r.GetHeader().Scene, "vis4gs-demo");
  EXPECT_EQ(r.GetHeader().Iterations, 2000);
  const std::vector<int> snaps = r.GetSnapshotIterations();
  ASSERT_EQ(snaps.size(), 11u);
  EXPECT_EQ(snaps.back(), 2000);
  EXPECT_EQ(r.GetSnapshotShDegree(2000), 3);
  EXPECT_EQ(r.GetSnapshotShDegree(1000), 0);
  EXPECT_EQ(r.GetImageNames().size(), 35u);
  // What the demo promises (issue 21): views like a capture's, tens of thousands of Gaussians.
  for (const Camera& camera : r.ReadCameras())
  {
    EXPECT_GE(camera.Width, 512) << camera.Name;
    EXPECT_GE(camera.Height, 512) << camera.Name;
  }
  EXPECT_GE(r.ReadSnapshot(2000).Count, 20000u);
  const MetricsTable train = r.ReadMetrics(false), test = r.ReadMetrics(true);
  ASSERT_EQ(train.Size(), 21u);
  EXPECT_GT(train.Psnr.back(), 25.0);
  EXPECT_LT(test.Psnr.back(), train.Psnr.back()); // the sparse sector shows in the test views
  EXPECT_TRUE(std::isnan(train.Lpips.back()));
  const EventTable ev = r.ReadEvents();
  std::set<std::int64_t> alive;
  for (std::int64_t id : r.ReadSnapshot(0).Ids)
  {
    alive.insert(id);
  }
  for (std::size_t k = 0; k < ev.Size(); ++k)
  {
    const TrainingEvent e = ev.Get(k);
    ASSERT_TRUE(alive.count(e.Parent)) << "event row " << k;
    if (e.Kind == EventKind::Prune)
    {
      alive.erase(e.Parent);
    }
    else
    {
      alive.insert(e.Child);
    }
  }
  for (std::size_t k = 0; k < ev.Size(); ++k)
  {
    if (ev.Kind[k] == 2)
    {
      alive.erase(ev.Parent[k]); // a split ends its parent
    }
  }
  const GaussianCloud last = r.ReadSnapshot(2000);
  EXPECT_EQ(std::set<std::int64_t>(last.Ids.begin(), last.Ids.end()), alive);
}
