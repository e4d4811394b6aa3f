#include "sph/solvers/solver.hpp"

#include "sph/assert.hpp"
#include "sph/solvers/dfsph.hpp"
#include "sph/solvers/seed.hpp"
#include "sph/solvers/wcsph.hpp"

#include <array>
#include <stdexcept>

namespace sph {

namespace {
// The solvers, in the order the README lists them.
constexpr std::array<const SolverCapabilities*, 3> solvers{&seed_capabilities, &wcsph_capabilities,
                                                           &dfsph_capabilities};
} // namespace

std::vector<std::string> solver_names() {
    std::vector<std::string> names;
    for (const auto* solver : solvers)
        names.emplace_back(solver->name);
    return names;
}

const SolverCapabilities& solver_capabilities(SolverKind kind) {
    const SolverCapabilities& solver = *solvers.at(static_cast<std::size_t>(kind));
    SPHCLIP_ASSERT(solver.kind == kind);
    return solver;
}

template <int D>
std::unique_ptr<Solver<D>> make_solver(SolverKind kind, const Params<D>& params) {
    switch (kind) {
    case SolverKind::seed:
        return std::make_unique<SeedSolver<D>>(params.kernel);
    case SolverKind::wcsph:
        return std::make_unique<WcsphSolver<D>>(params.kernel, params.cell_skin > 0);
    case SolverKind::dfsph:
        return std::make_unique<DfsphSolver<D>>(params.kernel);
    }
    throw std::invalid_argument("unknown solver");
}

template std::unique_ptr<Solver<2>> make_solver<2>(SolverKind, const Params<2>&);
template std::unique_ptr<Solver<3>> make_solver<3>(SolverKind, const Params<3>&);

} // namespace sph
