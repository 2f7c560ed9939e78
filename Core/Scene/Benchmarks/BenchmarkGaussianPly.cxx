// SPDX-License-Identifier: BSD-3-Clause
/**
 * Benchmark: reading a synthetic SH-degree-3 3DGS PLY (the trainer's 62 float32 properties)
 * from the page cache with ReadGaussianPly, against a straightforward reader (std::ifstream,
 * one read() per property value) in the same run. Each measurement runs in a fresh process
 * (this program re-executes itself) so that peak RSS (VmHWM) belongs to that reader alone;
 * the VmHWM of an idle child is reported and subtracted.
 *
 * Usage: BenchmarkGaussianPly [--gaussians=1000000,5000000] [--dir=/tmp] [--repeat=3]
 *                             [--keep]   (keep the generated files for the next run)
 */
#include "GaussianIO.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{

long VmHWMkB()
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
  {
    if (line.compare(0, 6, "VmHWM:") == 0)
    {
      return std::atol(line.c_str() + 6);
    }
  }
  return -1;
}

double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The straightforward reader: parse the header with getline, decide each property's
// destination once, then one istream::read per value into the same structure-of-arrays layout
// (SH reordered to coefficient-major). Single-threaded.
vis4gs::GaussianCloud NaiveRead(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t n = 0;
  std::vector<std::string> props;
  while (std::getline(in, line) && line != "end_header")
  {
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw == "element")
    {
      std::string name;
      ls >> name >> n;
    }
    else if (kw == "property")
    {
      std::string type, name;
      ls >> type >> name;
      props.push_back(name);
    }
  }
  int nRest = 0;
  for (const auto& p : props)
  {
    nRest += p.compare(0, 7, "f_rest_") == 0;
  }
  const int k = nRest / 3 + 1;
  vis4gs::GaussianCloud c;
  c.Count = n;
  c.ShDegree = k == 16 ? 3 : k == 9 ? 2 : k == 4 ? 1 : 0;
  c.Positions.resize(3 * n);
  c.LogScales.resize(3 * n);
  c.Rotations.resize(4 * n);
  c.OpacityLogits.resize(n);
  c.SH.resize(3 * k * n);
  vis4gs::ExtraProperty normals[3];
  for (int i = 0; i < 3; ++i)
  {
    normals[i].Name = std::string("n") + static_cast<char>('x' + i);
    normals[i].Bytes.resize(4 * n);
  }
  // Destination of each property, decided once from its name.
  std::vector<float*> base(props.size(), nullptr);
  std::vector<std::size_t> stride(props.size(), 0), offset(props.size(), 0);
  for (std::size_t i = 0; i < props.size(); ++i)
  {
    const std::string& p = props[i];
    if (p == "x" || p == "y" || p == "z")
    {
      base[i] = c.Positions.data(), stride[i] = 3, offset[i] = p[0] - 'x';
    }
    else if (p == "nx" || p == "ny" || p == "nz")
    {
      base[i] = reinterpret_cast<float*>(normals[p[1] - 'x'].Bytes.data()), stride[i] = 1;
    }
    else if (p.compare(0, 5, "f_dc_") == 0)
    {
      base[i] = c.SH.data(), stride[i] = 3 * k, offset[i] = p[5] - '0';
    }
    else if (p.compare(0, 7, "f_rest_") == 0)
    {
      const int j = std::atoi(p.c_str() + 7);
      base[i] = c.SH.data(), stride[i] = 3 * k, offset[i] = 3 * (j % (k - 1) + 1) + j / (k - 1);
    }
    else if (p == "opacity")
    {
      base[i] = c.OpacityLogits.data(), stride[i] = 1;
    }
    else if (p.compare(0, 6, "scale_") == 0)
    {
      base[i] = c.LogScales.data(), stride[i] = 3, offset[i] = p[6] - '0';
    }
    else if (p.compare(0, 4, "rot_") == 0)
    {
      base[i] = c.Rotations.data(), stride[i] = 4, offset[i] = p[4] - '0';
    }
  }
  for (std::size_t g = 0; g < n; ++g)
  {
    for (std::size_t i = 0; i < props.size(); ++i)
    {
      float v;
      in.read(reinterpret_cast<char*>(&v), 4);
      if (base[i])
      {
        base[i][g * stride[i] + offset[i]] = v;
      }
    }
  }
  if (!in)
  {
    throw std::runtime_error(path + ": short read");
  }
  for (auto& e : normals)
  {
    c.Extra.push_back(std::move(e));
  }
  return c;
}

std::size_t KeptBytes(const vis4gs::GaussianCloud& c)
{
  std::size_t b = 4 *
    (c.Positions.size() + c.LogScales.size() + c.Rotations.size() + c.OpacityLogits.size() +
      c.SH.size());
  for (const auto& e : c.Extra)
  {
    b += e.Bytes.size();
  }
  return b;
}

// Child modes: print "seconds keptBytes vmhwm_kB checksum".
int Child(const std::string& mode, const std::string& path)
{
  double t0 = Now();
  vis4gs::GaussianCloud c;
  if (mode == "ours")
  {
    c = vis4gs::ReadGaussianPly(path);
  }
  else if (mode == "naive")
  {
    c = NaiveRead(path);
  }
  const double t = Now() - t0;
  double sum = 0;
  for (std::size_t i = 0; i < c.SH.size(); i += 4099)
  {
    sum += c.SH[i];
  }
  for (std::size_t i = 0; i < c.Positions.size(); i += 997)
  {
    sum += c.Positions[i];
  }
  rusage ru;
  ::getrusage(RUSAGE_SELF, &ru);
  const double cpu = ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec + ru.ru_stime.tv_sec +
    1e-6 * ru.ru_stime.tv_usec;
  std::printf("%.6f %zu %ld %.9g %.6f\n", t, KeptBytes(c), VmHWMkB(), sum, cpu);
  return 0;
}

struct Result
{
  double Seconds = 0;
  std::size_t Kept = 0;
  long HwmKB = 0;
  double Checksum = 0;
  double CpuSeconds = 0; // user + system of the whole child process
};

Result RunChild(const std::string& self, const std::string& mode, const std::string& path)
{
  const std::string cmd = "'" + self + "' --child=" + mode + " '" + path + "'";
  FILE* p = ::popen(cmd.c_str(), "r");
  Result r;
  if (!p ||
    std::fscanf(
      p, "%lf %zu %ld %lf %lf", &r.Seconds, &r.Kept, &r.HwmKB, &r.Checksum, &r.CpuSeconds) != 5)
  {
    std::cerr << "child failed: " << cmd << "\n";
    std::exit(1);
  }
  ::pclose(p);
  return r;
}

void Generate(const std::string& path, std::size_t n)
{
  // In a child process so that the parent stays small.
  const pid_t pid = ::fork();
  if (pid == 0)
  {
    vis4gs::GaussianCloud c;
    c.Resize(n, 3);
    std::mt19937 rng(1);
    std::normal_distribution<float> g(0.0f, 1.0f);
    for (auto* v : { &c.Positions, &c.LogScales, &c.Rotations, &c.OpacityLogits, &c.SH })
    {
      for (float& x : *v)
      {
        x = g(rng);
      }
    }
    for (const char* nn : { "nx", "ny", "nz" })
    {
      vis4gs::ExtraProperty e;
      e.Name = nn;
      e.Bytes.assign(4 * n, 0);
      c.Extra.push_back(std::move(e));
    }
    vis4gs::WriteGaussianPly(path, c);
    std::_Exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    std::cerr << "generation failed\n";
    std::exit(1);
  }
}

void WarmPageCache(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buf(1 << 22);
  while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0)
  {
  }
}

} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::size_t> sizes = { 1000000, 5000000 };
  std::string dir = "/tmp";
  int repeat = 3;
  bool keep = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a.compare(0, 8, "--child=") == 0 && i + 1 < argc)
    {
      return Child(a.substr(8), argv[i + 1]);
    }
    if (a.compare(0, 12, "--gaussians=") == 0)
    {
      sizes.clear();
      std::stringstream ss(a.substr(12));
      std::string item;
      while (std::getline(ss, item, ','))
      {
        sizes.push_back(std::stoull(item));
      }
    }
    else if (a.compare(0, 6, "--dir=") == 0)
    {
      dir = a.substr(6);
    }
    else if (a.compare(0, 9, "--repeat=") == 0)
    {
      repeat = std::max(1, std::atoi(a.c_str() + 9));
    }
    else if (a == "--keep")
    {
      keep = true;
    }
    else
    {
      std::cerr << "usage: " << argv[0]
                << " [--gaussians=N,M] [--dir=/tmp] [--repeat=3] [--keep]\n";
      return 2;
    }
  }
  char selfPath[4096];
  const ssize_t len = ::readlink("/proc/self/exe", selfPath, sizeof(selfPath) - 1);
  if (len <= 0)
  {
    return 1;
  }
  selfPath[len] = 0;
  const char* threads = std::getenv("OMP_NUM_THREADS");
  std::printf("ReadGaussianPly benchmark, OMP_NUM_THREADS=%s, %ld online CPUs\n",
    threads ? threads : "(unset)",
    ::sysconf(_SC_NPROCESSORS_ONLN));
  const Result idle = RunChild(selfPath, "none", "-");
  std::printf("idle child VmHWM: %.1f MiB (subtracted below)\n", idle.HwmKB / 1024.0);
  for (std::size_t n : sizes)
  {
    const std::string path = dir + "/vis4gs-bench-sh3-" + std::to_string(n) + ".ply";
    struct stat st;
    if (::stat(path.c_str(), &st) != 0)
    {
      Generate(path, n);
      ::stat(path.c_str(), &st);
    }
    const double gb = st.st_size / 1e9;
    std::printf("\n%zu Gaussians, SH degree 3, %.3f GB (%s)\n", n, gb, path.c_str());
    for (const char* mode : { "ours", "naive" })
    {
      std::vector<double> times;
      double bestCpu = 1e300;
      Result last;
      for (int r = 0; r < repeat; ++r)
      {
        WarmPageCache(path);
        last = RunChild(selfPath, mode, path);
        times.push_back(last.Seconds);
        bestCpu = std::min(bestCpu, last.CpuSeconds);
      }
      std::sort(times.begin(), times.end());
      const double best = times.front();
      const double median = times[times.size() / 2];
      const double peak = (last.HwmKB - idle.HwmKB) * 1024.0;
      std::printf("  %-6s best %.3f s (%.2f GB/s), median %.3f s, least CPU (user+sys) %.3f s, "
                  "peak RSS above idle %.0f MiB = %.3f x kept arrays (%.0f MiB), checksum %.6g\n",
        mode,
        best,
        gb / best,
        median,
        bestCpu,
        peak / 1048576.0,
        peak / last.Kept,
        last.Kept / 1048576.0,
        last.Checksum);
      std::fflush(stdout);
    }
    if (!keep)
    {
      std::remove(path.c_str());
    }
  }
  return 0;
}
