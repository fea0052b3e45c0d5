#include "bench/budget/memory_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ltm::bench {
namespace {

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

// A round step giving about `n` ticks over [0, hi].
double tick_step(double hi, int n) {
    const double raw = hi / n, p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= raw) return m * p;
    return 10 * p;
}

std::string num(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

}  // namespace

void write_memory_svg(std::ostream& out, const std::string& title,
                      const std::vector<MemoryCurve>& curves, double budget_mb) {
    const double W = 800, H = 450, L = 70, R = 20, T = 40, B = 50;
    double t_max = 1, m_max = budget_mb > 0 ? budget_mb * 1.1 : 1;
    for (const auto& c : curves) {
        for (double t : c.t_s) t_max = std::max(t_max, t);
        for (double m : c.rss_mb) m_max = std::max(m_max, m * 1.05);
    }
    auto X = [&](double t) { return L + (W - L - R) * t / t_max; };
    auto Y = [&](double m) { return H - B - (H - T - B) * m / m_max; };
    const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"" << W / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">"
        << escape(title) << "</text>\n";
    const double ts = tick_step(t_max, 8), ms = tick_step(m_max, 6);
    for (double t = 0; t <= t_max + 1e-9; t += ts)
        out << "<line x1=\"" << X(t) << "\" y1=\"" << T << "\" x2=\"" << X(t) << "\" y2=\"" << H - B
            << "\" stroke=\"#eee\"/><text x=\"" << X(t) << "\" y=\"" << H - B + 16
            << "\" text-anchor=\"middle\">" << num(t) << "</text>\n";
    for (double m = 0; m <= m_max + 1e-9; m += ms)
        out << "<line x1=\"" << L << "\" y1=\"" << Y(m) << "\" x2=\"" << W - R << "\" y2=\"" << Y(m)
            << "\" stroke=\"#eee\"/><text x=\"" << L - 6 << "\" y=\"" << Y(m) + 4
            << "\" text-anchor=\"end\">" << num(m) << "</text>\n";
    out << "<rect x=\"" << L << "\" y=\"" << T << "\" width=\"" << W - L - R << "\" height=\""
        << H - T - B << "\" fill=\"none\" stroke=\"black\"/>\n"
        << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 12
        << "\" text-anchor=\"middle\">time since the host started [s]</text>\n"
        << "<text x=\"16\" y=\"" << (T + H - B) / 2
        << "\" text-anchor=\"middle\" transform=\"rotate(-90 16 " << (T + H - B) / 2
        << ")\">resident memory [MB]</text>\n";
    if (budget_mb > 0)
        out << "<line x1=\"" << L << "\" y1=\"" << Y(budget_mb) << "\" x2=\"" << W - R << "\" y2=\""
            << Y(budget_mb) << "\" stroke=\"black\" stroke-dasharray=\"6 4\"/>"
            << "<text x=\"" << W - R - 4 << "\" y=\"" << Y(budget_mb) - 5
            << "\" text-anchor=\"end\">budget " << num(budget_mb) << " MB</text>\n";
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const auto& c = curves[i];
        const char* colour = colours[i % 6];
        out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
        for (std::size_t k = 0; k < c.t_s.size() && k < c.rss_mb.size(); ++k)
            out << X(c.t_s[k]) << ',' << Y(c.rss_mb[k]) << ' ';
        out << "\"/>\n<text x=\"" << L + 10 << "\" y=\"" << T + 18 + 16 * i << "\" fill=\""
            << colour << "\">" << escape(c.label) << "</text>\n";
    }
    out << "</svg>\n";
}

}  // namespace ltm::bench
