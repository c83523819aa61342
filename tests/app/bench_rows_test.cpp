// `pba bench`'s swarm table and its note on a run the machine's speed split: rows built by hand,
// so a spread can be asked for (a real run shows one only when the bandwidth changes level).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/bench_rows.hpp"

using pba::app::bench::Row;

namespace {

Row swarmRow(std::size_t n, double best, double median)
{
    Row row;
    row.layout = "swarm";
    row.integrator = "semi-implicit-euler";
    row.phase = "landed";
    row.n = n;
    row.threads = 2;
    row.rate = best;
    row.medianRate = median;
    row.ofBound = 0.5;
    return row;
}

int lines(const std::string& text)
{
    int count = 0;
    for (char c : text)
        count += c == '\n';
    return count;
}

} // namespace

TEST(BenchRows, SteadyRowsGetNoNote)
{
    // 1.25 times the median is still one level: a few percent of noise and the odd slow window.
    const std::vector<Row> rows{swarmRow(1000000, 2.5e9, 2.4e9), swarmRow(10000000, 1.25e9, 1.0e9)};
    EXPECT_EQ(pba::app::bench::spreadNotes(rows), "");
}

TEST(BenchRows, ASplitRunGetsOneNoteForItsSize)
{
    // At 1e7 one row's best window came at the high level (2.2e9) and its median at the low one.
    const std::vector<Row> rows{swarmRow(1000000, 2.5e9, 2.4e9), swarmRow(10000000, 2.2e9, 1.4e9),
                                swarmRow(10000000, 1.6e9, 1.4e9)};
    const std::string notes = pba::app::bench::spreadNotes(rows);
    EXPECT_EQ(lines(notes), 1) << notes;
    EXPECT_NE(notes.find("N = 10000000"), std::string::npos) << notes;
    EXPECT_NE(notes.find("1.57 times its median"), std::string::npos) << notes; // the widest row's
    EXPECT_EQ(notes.find("N = 1000000 "), std::string::npos) << notes;
}

TEST(BenchRows, RowsWithoutAMedianAreLeftOut)
{
    Row unmeasured = swarmRow(1000000, 2.5e9, 0.0);
    EXPECT_EQ(pba::app::bench::spreadNotes({unmeasured}), "");
}

TEST(BenchRows, TheTableHasAHeaderAndALineARowWithBlankUnmeasuredColumns)
{
    Row bound;
    bound.layout = "bound";
    bound.n = 1000;
    bound.rate = 4e9;
    bound.medianRate = 3.9e9;
    const std::string text = pba::app::bench::table({bound, swarmRow(1000, 2e9, 1.9e9)});
    EXPECT_EQ(lines(text), 3) << text;
    EXPECT_NE(text.find("particle-steps/s"), std::string::npos);
    EXPECT_NE(text.find("4.000e+09"), std::string::npos) << text;
    EXPECT_NE(text.find("0.50"), std::string::npos) << text; // the swarm's of bound
    // The bound's line ends with its median: no ratio to itself nor to the baseline, no bytes.
    const std::size_t from = text.find("\nbound") + 1; // the header's "of bound" is not the row
    const std::string boundLine = text.substr(from, text.find('\n', from) - from);
    const std::size_t median = boundLine.find("3.900e+09");
    ASSERT_NE(median, std::string::npos) << boundLine;
    EXPECT_EQ(boundLine.find_first_not_of(' ', median + 9), std::string::npos) << boundLine;
}
