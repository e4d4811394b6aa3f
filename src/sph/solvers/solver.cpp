#include "sph/solvers/solver.hpp"

#include "sph/solvers/dfsph.hpp"
#include "sph/solvers/seed.hpp"
#include "sph/solvers/wcsph.hpp"

#include <stdexcept>

namespace sph {

std::vector<std::string> solver_names() {
    return {"seed", "wcsph", "dfsph"};
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
