#include "sph/solvers/solver.hpp"

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

const SolverCapabilities& solver_capabilities(std::string_view name) {
    for (const auto* solver : solvers)
        if (solver->name == name)
            return *solver;
    throw std::invalid_argument("unknown solver: " + std::string(name));
}

template <int D>
std::unique_ptr<Solver<D>> make_solver(std::string_view name, const Params<D>& params) {
    if (name == "seed")
        return std::make_unique<SeedSolver<D>>(params.kernel);
    if (name == "wcsph")
        return std::make_unique<WcsphSolver<D>>(params.kernel);
    if (name == "dfsph")
        return std::make_unique<DfsphSolver<D>>(params.kernel);
    throw std::invalid_argument("unknown solver: " + std::string(name));
}

template std::unique_ptr<Solver<2>> make_solver<2>(std::string_view, const Params<2>&);
template std::unique_ptr<Solver<3>> make_solver<3>(std::string_view, const Params<3>&);

} // namespace sph
