#include "output/particle_export.hpp"

#include "output/files.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <libdeflate.h>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace sph {

std::string frame_stem(std::uint64_t frame) {
    return fmt::format("frame_{:05d}", frame);
}

namespace {

// The particles by ascending id: the files do not depend on the order the
// particles sit in memory (the simulation sorts it by cell now and then).
std::vector<std::size_t> by_id(const Snapshot& f) {
    std::vector<std::size_t> rows(f.size());
    std::iota(rows.begin(), rows.end(), std::size_t(0));
    if (f.id.size() == rows.size())
        std::sort(rows.begin(), rows.end(),
                  [&f](std::size_t a, std::size_t b) { return f.id[a] < f.id[b]; });
    return rows;
}

} // namespace

void ParticleCsv::write(const Snapshot& f) {
    const int dim = f.dimension;
    fmt::memory_buffer out;
    // id and time come last, so scripts that read the first columns by
    // position keep working.
    fmt::format_to(std::back_inserter(out), "{}\n",
                   dim == 2 ? "x,y,vx,vy,density,pressure,id,time"
                            : "x,y,z,vx,vy,vz,density,pressure,id,time");
    const std::string time = fmt::format("{:.9g}", f.time);
    for (const std::size_t i : by_id(f)) {
        for (int a = 0; a < dim; ++a)
            fmt::format_to(std::back_inserter(out), "{:.9g},", f.position[i * dim + a]);
        for (int a = 0; a < dim; ++a)
            fmt::format_to(std::back_inserter(out), "{:.9g},", f.velocity[i * dim + a]);
        fmt::format_to(std::back_inserter(out), "{:.9g},{:.9g},{},{}\n", f.density[i],
                       f.pressure[i], f.id.empty() ? std::uint64_t(i) : std::uint64_t(f.id[i]),
                       time);
    }
    write_file_atomically(folder_ / "particles" / (frame_stem(f.frame) + ".csv"),
                          std::string_view(out.data(), out.size()));
}

namespace {

// One array of a .vtp file: its XML attributes and its values, as the
// little-endian bytes of `type`.
struct VtkArray {
    std::string attributes; // type="Float64" Name="velocity" NumberOfComponents="3"
    std::string bytes;
};

template <class T>
void append_value(std::string& bytes, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T)); // x86 and ARM are little-endian, as the files say
    bytes.append(raw, sizeof(T));
}

// Vectors are written with 3 components (z = 0 in 2D), as VTK expects.
VtkArray vector_array(const char* name, const std::vector<double>& v, int dim,
                      const std::vector<std::size_t>& rows) {
    VtkArray array{fmt::format("type=\"Float64\"{} NumberOfComponents=\"3\"",
                               name ? fmt::format(" Name=\"{}\"", name) : std::string()),
                   {}};
    array.bytes.reserve(rows.size() * 24);
    for (const std::size_t i : rows)
        for (int a = 0; a < 3; ++a)
            append_value(array.bytes, a < dim ? v[i * dim + a] : 0.0);
    return array;
}

// VTK's zlib compression, as vtkZLibDataCompressor lays it out with
// header_type UInt64: [blocks, block size, size of a partial last block (0:
// none), compressed size of each block], then the zlib streams. libdeflate
// (Debian's libdeflate-dev) writes zlib streams.
std::string vtk_compressed(const std::string& raw) {
    constexpr std::size_t block = 1 << 16;
    // Level 1: a 1M-particle frame is about 100 MB of arrays.
    thread_local const std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)>
        compressor{libdeflate_alloc_compressor(1), libdeflate_free_compressor};
    if (!compressor)
        throw std::runtime_error("cannot compress the VTK arrays: out of memory");
    const std::size_t blocks = (raw.size() + block - 1) / block;
    std::vector<std::uint64_t> header{blocks, block, raw.size() % block};
    std::string streams;
    std::vector<char> buffer(libdeflate_zlib_compress_bound(compressor.get(), block));
    for (std::size_t b = 0; b < blocks; ++b) {
        const std::size_t size = std::min(block, raw.size() - b * block);
        const std::size_t written = libdeflate_zlib_compress(
            compressor.get(), raw.data() + b * block, size, buffer.data(), buffer.size());
        if (written == 0)
            throw std::runtime_error("cannot compress the VTK arrays");
        header.push_back(written);
        streams.append(buffer.data(), written);
    }
    std::string out;
    for (const std::uint64_t h : header)
        append_value(out, h);
    return out + streams;
}

template <class T>
std::string ascii_values(const std::string& bytes, std::size_t per_line) {
    fmt::memory_buffer out;
    const std::size_t n = bytes.size() / sizeof(T);
    for (std::size_t k = 0; k < n; ++k) {
        T v;
        std::memcpy(&v, bytes.data() + k * sizeof(T), sizeof(T));
        if constexpr (std::is_floating_point_v<T>)
            fmt::format_to(std::back_inserter(out), "{:.9g}", v);
        else
            fmt::format_to(std::back_inserter(out), "{}", v);
        out.push_back((k + 1) % per_line == 0 ? '\n' : ' ');
    }
    return std::string(out.data(), out.size());
}

// The array's values as text, for vtk-ascii.
std::string ascii_array(const VtkArray& array) {
    const std::size_t per_line =
        array.attributes.find("NumberOfComponents=\"3\"") != std::string::npos ? 3 : 1;
    if (array.attributes.starts_with("type=\"Float64\""))
        return ascii_values<double>(array.bytes, per_line);
    if (array.attributes.starts_with("type=\"Int64\""))
        return ascii_values<std::int64_t>(array.bytes, per_line);
    return ascii_values<std::uint32_t>(array.bytes, per_line);
}

} // namespace

void ParticleVtk::write(const Snapshot& f) {
    const int dim = f.dimension;
    const std::size_t n = f.size();
    const std::vector<std::size_t> rows = by_id(f);

    VtkArray points = vector_array(nullptr, f.position, dim, rows);
    // One vertex cell per particle, so ParaView draws the points directly.
    VtkArray connectivity{"type=\"Int64\" Name=\"connectivity\"", {}},
        offsets{"type=\"Int64\" Name=\"offsets\"", {}};
    for (std::size_t i = 0; i < n; ++i) {
        append_value(connectivity.bytes, std::int64_t(i));
        append_value(offsets.bytes, std::int64_t(i + 1));
    }
    std::vector<VtkArray> point_data;
    point_data.push_back(vector_array("velocity", f.velocity, dim, rows));
    for (const auto& [name, values] :
         {std::pair{"density", &f.density}, std::pair{"pressure", &f.pressure}}) {
        VtkArray array{fmt::format("type=\"Float64\" Name=\"{}\"", name), {}};
        if (!values->empty())
            for (const std::size_t i : rows)
                append_value(array.bytes, (*values)[i]);
        point_data.push_back(std::move(array));
    }
    VtkArray ids{"type=\"UInt32\" Name=\"id\"", {}};
    for (const std::size_t i : rows)
        append_value(ids.bytes, f.id.empty() ? std::uint32_t(i) : f.id[i]);
    point_data.push_back(std::move(ids));

    const bool binary = encoding_ == Encoding::binary;
    std::string appended; // the arrays' compressed bytes, in the order of the XML
    fmt::memory_buffer out;
    auto put = [&out]<class... Args>(fmt::format_string<Args...> format, Args&&... args) {
        fmt::format_to(std::back_inserter(out), format, std::forward<Args>(args)...);
    };
    auto data_array = [&](const VtkArray& array) {
        if (binary) {
            put("<DataArray {} format=\"appended\" offset=\"{}\"/>\n", array.attributes,
                appended.size());
            appended += vtk_compressed(array.bytes);
        } else {
            put("<DataArray {} format=\"ascii\">\n{}</DataArray>\n", array.attributes,
                ascii_array(array));
        }
    };
    put("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
        "byte_order=\"LittleEndian\"{}>\n",
        binary ? " header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"" : "");
    put("<PolyData>\n<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
        "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
        n, n);
    put("<Points>\n");
    data_array(points);
    put("</Points>\n<Verts>\n");
    data_array(connectivity);
    data_array(offsets);
    put("</Verts>\n<PointData Scalars=\"density\" Vectors=\"velocity\">\n");
    for (const VtkArray& array : point_data)
        data_array(array);
    put("</PointData>\n</Piece>\n</PolyData>\n");
    if (binary) {
        // Raw bytes after an underscore, as the format defines them.
        put("<AppendedData encoding=\"raw\">\n_");
        out.append(appended.data(), appended.data() + appended.size());
        put("\n</AppendedData>\n");
    }
    put("</VTKFile>\n");

    const std::string file = "particles/" + frame_stem(f.frame) + ".vtp";
    write_file_atomically(folder_ / file, std::string_view(out.data(), out.size()));

    written_.emplace_back(f.time, file);
    fmt::memory_buffer pvd;
    fmt::format_to(std::back_inserter(pvd),
                   "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" "
                   "byte_order=\"LittleEndian\">\n<Collection>\n");
    for (const auto& [time, name] : written_)
        fmt::format_to(std::back_inserter(pvd),
                       "<DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", time, name);
    fmt::format_to(std::back_inserter(pvd), "</Collection>\n</VTKFile>\n");
    write_file_atomically(folder_ / "particles.pvd", std::string_view(pvd.data(), pvd.size()));
}

} // namespace sph
