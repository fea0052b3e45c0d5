#include "evaluation/core/html_report.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

TEST(HtmlReport, EscapesAndEncodes) {
    EXPECT_EQ(html_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("M"), "TQ==");
    EXPECT_EQ(base64("Ma"), "TWE=");
    EXPECT_EQ(base64("Man"), "TWFu");
    EXPECT_EQ(base64(std::string("\xff\x00\x10", 3)), "/wAQ");
}

TEST(HtmlReport, SectionsContentsAndEmbeddedPictures) {
    HtmlReport r("run <1>");
    r.section("What ran");
    r.table({"key", "value"}, {{"launch", "robot_lifelong.yaml"}, {"x<y", "1"}});
    r.section("Map");
    r.svg("<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>", "a picture");
    r.collapsed("host.log", "line <1>\nline 2");
    r.files({{"slam_tum.txt", 2048}, {"map/graph.bin", 3u << 20}});
    const std::string html = r.html();
    EXPECT_EQ(r.sections(), 2u);
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(html.find("<title>run &lt;1&gt;</title>"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"#s1\">Map</a>"), std::string::npos);
    EXPECT_NE(html.find("<td>x&lt;y</td>"), std::string::npos);
    EXPECT_NE(html.find("src=\"data:image/svg+xml;base64,"), std::string::npos);
    EXPECT_NE(html.find("line &lt;1&gt;"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"map/graph.bin\">"), std::string::npos);
    EXPECT_NE(html.find("2.0 kB"), std::string::npos);
    EXPECT_NE(html.find("3.0 MB"), std::string::npos);
    // Self-contained: nothing is fetched (no src or href to another host).
    EXPECT_EQ(html.find("src=\"http"), std::string::npos);
    EXPECT_EQ(html.find("href=\"http"), std::string::npos);
    // Every section is closed.
    std::size_t open = 0, closed = 0;
    for (std::size_t p = 0; (p = html.find("<section", p)) != std::string::npos; ++p) ++open;
    for (std::size_t p = 0; (p = html.find("</section>", p)) != std::string::npos; ++p) ++closed;
    EXPECT_EQ(open, 2u);
    EXPECT_EQ(closed, 2u);
}

}  // namespace
}  // namespace ltm::eval
