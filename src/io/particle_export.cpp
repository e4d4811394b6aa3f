#include "io/particle_export.hpp"

#include "io/files.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <numeric>
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
    fmt::format_to(std::back_inserter(out), "{}\n",
                   dim == 2 ? "x,y,vx,vy,density,pressure" : "x,y,z,vx,vy,vz,density,pressure");
    for (const std::size_t i : by_id(f)) {
        for (int a = 0; a < dim; ++a)
            fmt::format_to(std::back_inserter(out), "{:.9g},", f.position[i * dim + a]);
        for (int a = 0; a < dim; ++a)
            fmt::format_to(std::back_inserter(out), "{:.9g},", f.velocity[i * dim + a]);
        fmt::format_to(std::back_inserter(out), "{:.9g},{:.9g}\n", f.density[i], f.pressure[i]);
    }
    write_file_atomically(folder_ / "particles" / (frame_stem(f.frame) + ".csv"),
                          std::string_view(out.data(), out.size()));
}

void ParticleVtk::write(const Snapshot& f) {
    const int dim = f.dimension;
    const std::size_t n = f.size();
    const std::vector<std::size_t> rows = by_id(f);
    fmt::memory_buffer out;
    auto put = [&out]<class... Args>(fmt::format_string<Args...> format, Args&&... args) {
        fmt::format_to(std::back_inserter(out), format, std::forward<Args>(args)...);
    };
    // Vectors are written with 3 components (z = 0 in 2D), as VTK expects.
    auto vectors = [&](const std::vector<double>& v) {
        for (const std::size_t i : rows)
            put("{:.9g} {:.9g} {:.9g}\n", v[i * dim], v[i * dim + 1],
                dim == 3 ? v[i * dim + 2] : 0.0);
    };
    put("<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
        "<PolyData>\n<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
        "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
        n, n);
    put("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    vectors(f.position);
    put("</DataArray>\n</Points>\n");
    // One vertex cell per particle, so ParaView draws the points directly.
    put("<Verts>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i)
        put("{}\n", i);
    put("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i)
        put("{}\n", i + 1);
    put("</DataArray>\n</Verts>\n");
    put("<PointData Scalars=\"density\" Vectors=\"velocity\">\n");
    put("<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" "
        "format=\"ascii\">\n");
    vectors(f.velocity);
    put("</DataArray>\n");
    for (const auto& [name, values] :
         {std::pair{"density", &f.density}, std::pair{"pressure", &f.pressure}}) {
        put("<DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
        if (!values->empty())
            for (const std::size_t i : rows)
                put("{:.9g}\n", (*values)[i]);
        put("</DataArray>\n");
    }
    put("<DataArray type=\"UInt32\" Name=\"id\" format=\"ascii\">\n");
    for (const std::size_t i : rows)
        put("{}\n", f.id[i]);
    put("</DataArray>\n</PointData>\n</Piece>\n</PolyData>\n</VTKFile>\n");

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
