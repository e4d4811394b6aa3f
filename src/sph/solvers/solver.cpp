#include "sph/solvers/solver.hpp"

#include "sph/solvers/seed.hpp"

#include <stdexcept>

namespace sph {

std::vector<std::string> solver_names() {
    return {"seed"};
}

template <int D>
std::unique_ptr<Solver<D>> make_solver(std::string_view name) {
    if (name == "seed")
        return std::make_unique<SeedSolver<D>>();
    throw std::invalid_argument("unknown solver: " + std::string(name));
}

template std::unique_ptr<Solver<2>> make_solver<2>(std::string_view);
template std::unique_ptr<Solver<3>> make_solver<3>(std::string_view);

} // namespace sph
