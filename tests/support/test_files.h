#pragma once
// Test helpers (header-only, shared by tests/io and tests/cli): temporary folders, writers for
// small MRC/INR/raw files built byte by byte (so the readers are tested against the format
// specification, not against themselves), and running the isodel executable.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace isodel::test {

/// A fresh folder under $TMPDIR (or /tmp), removed with its contents on destruction.
class TempDir {
public:
    TempDir()
    {
        const char* base = std::getenv("TMPDIR");
        std::string tmpl = std::string(base && *base ? base : "/tmp") + "/isodel-test-XXXXXX";
        std::vector<char> buf(tmpl.begin(), tmpl.end());
        buf.push_back('\0');
        if (!::mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed");
        path_ = buf.data();
    }
    ~TempDir() { std::system(("rm -rf '" + path_ + "'").c_str()); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::string& path() const { return path_; }
    std::string operator/(const std::string& name) const { return path_ + "/" + name; }

private:
    std::string path_;
};

/// Names in a folder (without "." and "..").
inline std::vector<std::string> list_dir(const std::string& dir)
{
    std::vector<std::string> names;
    if (DIR* d = ::opendir(dir.c_str())) {
        while (dirent* e = ::readdir(d)) {
            const std::string n = e->d_name;
            if (n != "." && n != "..") names.push_back(n);
        }
        ::closedir(d);
    }
    return names;
}

inline bool file_exists(const std::string& p)
{
    struct stat st {};
    return ::stat(p.c_str(), &st) == 0;
}

inline std::string read_text(const std::string& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_bytes(const std::string& p, const std::string& bytes)
{
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

/// Appends \p v's bytes, optionally reversed (big-endian files on a little-endian host).
template <typename T>
void append(std::string& s, T v, bool big_endian = false)
{
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big_endian)
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    s.append(b, sizeof(T));
}

/// Description of a synthetic MRC file. Samples are given by a function of the file's
/// (column, row, section) index.
struct MrcSpec {
    std::array<int, 3> n{4, 3, 2};            // NC, NR, NS
    int mode = 2;
    std::array<int, 3> start{0, 0, 0};        // NCSTART, NRSTART, NSSTART
    std::array<int, 3> m{0, 0, 0};            // MX, MY, MZ; 0 = the dims along x, y, z
    std::array<float, 3> cell{0, 0, 0};       // 0 = m * voxel
    std::array<float, 3> voxel{1, 1, 1};
    std::array<float, 3> angles{90, 90, 90};
    std::array<int, 3> map{1, 2, 3};          // MAPC, MAPR, MAPS
    std::array<float, 3> origin{0, 0, 0};
    int nsymbt = 0;
    bool big_endian = false;
    std::string magic = "MAP ";
    bool stamp = true;                        // write the machine stamp
};

inline std::string mrc_bytes(const MrcSpec& s, const std::function<double(int, int, int)>& value)
{
    std::array<int, 3> dims_xyz{};
    for (int f = 0; f < 3; ++f) dims_xyz[s.map[f] - 1] = s.n[f];
    std::array<int, 3> m = s.m;
    std::array<float, 3> cell = s.cell;
    for (int a = 0; a < 3; ++a) {
        if (m[a] == 0) m[a] = dims_xyz[a];
        if (cell[a] == 0) cell[a] = s.voxel[a] * float(m[a]);
    }
    std::string h;
    const bool be = s.big_endian;
    for (int v : s.n) append<std::int32_t>(h, v, be);
    append<std::int32_t>(h, s.mode, be);
    for (int v : s.start) append<std::int32_t>(h, v, be);
    for (int v : m) append<std::int32_t>(h, v, be);
    for (float v : cell) append<float>(h, v, be);
    for (float v : s.angles) append<float>(h, v, be);
    for (int v : s.map) append<std::int32_t>(h, v, be);
    for (int w = 19; w < 23; ++w) append<std::int32_t>(h, 0, be); // dmin dmax dmean ispg
    append<std::int32_t>(h, s.nsymbt, be);
    while (h.size() < 196) append<std::int32_t>(h, 0, be);
    for (float v : s.origin) append<float>(h, v, be);
    h += s.magic.substr(0, 4);
    if (s.stamp) h += be ? std::string("\x11\x11\x00\x00", 4) : std::string("\x44\x44\x00\x00", 4);
    else h += std::string(4, '\0');
    h.resize(1024, '\0');
    h += std::string(std::size_t(s.nsymbt), 'S');
    for (int k = 0; k < s.n[2]; ++k)
        for (int j = 0; j < s.n[1]; ++j)
            for (int i = 0; i < s.n[0]; ++i) {
                const double v = value(i, j, k);
                switch (s.mode) {
                case 0: append<std::int8_t>(h, std::int8_t(v), be); break;
                case 1: append<std::int16_t>(h, std::int16_t(v), be); break;
                case 6: append<std::uint16_t>(h, std::uint16_t(v), be); break;
                default: append<float>(h, float(v), be); break;
                }
            }
    return h;
}

/// INRIMAGE-4 header (padded to 256 bytes) + samples, x fastest.
inline std::string inr_bytes(std::array<int, 3> dims, const std::string& type, int bits, const std::string& cpu,
                             std::array<double, 3> voxel, const std::function<double(int, int, int)>& value,
                             int vdim = 1)
{
    std::ostringstream hs;
    hs << "#INRIMAGE-4#{\nXDIM=" << dims[0] << "\nYDIM=" << dims[1] << "\nZDIM=" << dims[2] << "\nVDIM=" << vdim
       << "\nTYPE=" << type << "\nPIXSIZE=" << bits << " bits\nSCALE=2**0\nCPU=" << cpu << "\nVX=" << voxel[0]
       << "\nVY=" << voxel[1] << "\nVZ=" << voxel[2] << "\n";
    std::string h = hs.str();
    const std::string end = "##}\n";
    h.resize(((h.size() + end.size() + 255) / 256) * 256 - end.size(), '\n');
    h += end;
    const bool be = cpu == "sun" || cpu == "sgi";
    for (int k = 0; k < dims[2]; ++k)
        for (int j = 0; j < dims[1]; ++j)
            for (int i = 0; i < dims[0]; ++i)
                for (int c = 0; c < vdim; ++c) {
                    const double v = value(i, j, k);
                    if (type == "float" && bits == 32) append<float>(h, float(v), be);
                    else if (type == "float") append<double>(h, v, be);
                    else if (type == "unsigned fixed" && bits == 8) append<std::uint8_t>(h, std::uint8_t(v), be);
                    else if (type == "unsigned fixed" && bits == 16) append<std::uint16_t>(h, std::uint16_t(v), be);
                    else if (type == "signed fixed" && bits == 16) append<std::int16_t>(h, std::int16_t(v), be);
                    else if (type == "signed fixed" && bits == 32) append<std::int32_t>(h, std::int32_t(v), be);
                    else throw std::runtime_error("inr_bytes: unsupported test type");
                }
    return h;
}

/// Result of running a command: exit status and captured streams.
struct RunResult {
    int status = -1;
    std::string out, err;
};

inline std::string shell_quote(const std::string& s)
{
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

/// Runs \p command through the shell with stdout and stderr captured to files in \p scratch.
inline RunResult run(const std::string& command, const std::string& scratch)
{
    const std::string o = scratch + "/.stdout", e = scratch + "/.stderr";
    const int rc = std::system((command + " >" + shell_quote(o) + " 2>" + shell_quote(e)).c_str());
    RunResult r;
    r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : 128 + WTERMSIG(rc);
    r.out = read_text(o);
    r.err = read_text(e);
    std::remove(o.c_str());
    std::remove(e.c_str());
    return r;
}

/// Runs the isodel executable with \p args (already quoted as needed).
inline RunResult run_isodel(const std::string& args, const std::string& scratch)
{
    return run(shell_quote(ISODEL_CLI) + " " + args, scratch);
}

inline bool shared_data_present()
{
    return file_exists(std::string(ISODEL_SHARED_DATA) + "/manifest.json");
}

} // namespace isodel::test
