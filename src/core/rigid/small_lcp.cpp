#include "rigid/small_lcp.hpp"

#include <algorithm>
#include <cmath>

namespace pba::rigid {

namespace {

/// x over the active rows solves A_SS x_S = -b_S (Gaussian elimination with partial pivoting);
/// the others are 0. A redundant row (four points of one face on a body that turns three ways)
/// makes A_SS singular: a diagonal of a ten-billionth of its largest picks one solution.
void solveActive(const std::vector<double>& a, const std::vector<double>& b, std::size_t n,
                 const std::vector<char>& active, std::vector<double>& x)
{
    std::vector<std::size_t> s;
    double diagonal = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        if (active[i]) {
            s.push_back(i);
            diagonal = std::max(diagonal, a[i * n + i]);
        }
    const std::size_t m = s.size();
    std::vector<double> k(m * (m + 1));
    for (std::size_t r = 0; r < m; ++r) {
        for (std::size_t c = 0; c < m; ++c)
            k[r * (m + 1) + c] = a[s[r] * n + s[c]] + (r == c ? 1e-10 * diagonal : 0.0);
        k[r * (m + 1) + m] = -b[s[r]];
    }
    for (std::size_t col = 0; col < m; ++col) {
        std::size_t pivot = col;
        for (std::size_t r = col + 1; r < m; ++r)
            if (std::abs(k[r * (m + 1) + col]) > std::abs(k[pivot * (m + 1) + col]))
                pivot = r;
        for (std::size_t c = 0; c <= m; ++c)
            std::swap(k[col * (m + 1) + c], k[pivot * (m + 1) + c]);
        const double p = k[col * (m + 1) + col];
        if (p == 0.0)
            continue;
        for (std::size_t r = col + 1; r < m; ++r) {
            const double f = k[r * (m + 1) + col] / p;
            for (std::size_t c = col; c <= m; ++c)
                k[r * (m + 1) + c] -= f * k[col * (m + 1) + c];
        }
    }
    std::fill(x.begin(), x.end(), 0.0);
    for (std::size_t r = m; r-- > 0;) {
        double sum = k[r * (m + 1) + m];
        for (std::size_t c = r + 1; c < m; ++c)
            sum -= k[r * (m + 1) + c] * x[s[c]];
        const double p = k[r * (m + 1) + r];
        x[s[r]] = p != 0.0 ? sum / p : 0.0;
    }
}

} // namespace

void solveSmallLcp(const std::vector<double>& a, const std::vector<double>& b, std::size_t n, double tolerance,
                   std::vector<double>& x, std::size_t equalities)
{
    x.assign(n, 0.0);
    std::vector<char> active(n, 1);
    for (std::size_t round = 0; round < 4 * n + 4; ++round) {
        solveActive(a, b, n, active, x);
        std::size_t worst = n;
        for (std::size_t i = equalities; i < n; ++i)
            if (active[i] && x[i] < 0.0 && (worst == n || x[i] < x[worst]))
                worst = i;
        if (worst < n) {
            active[worst] = 0;
            continue;
        }
        double most = -tolerance;
        for (std::size_t i = equalities; i < n; ++i) {
            if (active[i])
                continue;
            double w = b[i];
            for (std::size_t j = 0; j < n; ++j)
                w += a[i * n + j] * x[j];
            if (w < most) {
                most = w;
                worst = i;
            }
        }
        if (worst == n)
            break;
        active[worst] = 1;
    }
    for (std::size_t i = equalities; i < n; ++i)
        x[i] = std::max(x[i], 0.0);
}

} // namespace pba::rigid
