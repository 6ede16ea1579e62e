// Students' text is data (voxlab/untrusted_text.h): names, compiler logs and
// messages become valid UTF-8, lose their control bytes on a terminal,
// never start a formula in the gradebook, never collide with the grader's
// own files as a folder name, and never break the writers of report.json,
// the HTML reports, the gradebook and the terminal summary.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "support/run_command.h"
#include "voxlab/grader.h"
#include "voxlab/html_report.h"
#include "voxlab/untrusted_text.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kLatin1 = "caf\xe9 cr\xe8me";  // Latin-1, not UTF-8

TEST(SafeText, InvalidUtf8BecomesTheReplacementCharacter) {
    EXPECT_EQ(safeText("plain ascii"), "plain ascii");
    EXPECT_EQ(safeText("caf\xc3\xa9"), "caf\xc3\xa9");  // valid UTF-8 is kept
    EXPECT_EQ(safeText(kLatin1), "caf\xef\xbf\xbd cr\xef\xbf\xbdme");
    EXPECT_EQ(safeText("\xc0\xaf"), "\xef\xbf\xbd\xef\xbf\xbd");       // an overlong '/'
    EXPECT_EQ(safeText("\xed\xa0\x80"), "\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd");  // a surrogate
    EXPECT_EQ(safeText("\xf4\x90\x80\x80"), "\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd");  // past U+10FFFF
    EXPECT_EQ(safeText("\xe2\x82"), "\xef\xbf\xbd");  // cut short: one replacement
    EXPECT_EQ(safeText(std::string("a\0b", 3)), std::string("a\0b", 3));
    for (const std::string& s : {kLatin1, std::string("\xff\xfe\xfd"), std::string("\xe2\x82\xac\xe2")})
        EXPECT_TRUE(isValidUtf8(safeText(s))) << s;
    EXPECT_FALSE(isValidUtf8(kLatin1));
}

TEST(SafeText, LongTextIsCutAtACharacterWithAMarker) {
    const std::string euros = [] {
        std::string s;
        for (int i = 0; i < 1000; ++i) s += "\xe2\x82\xac";  // 3000 bytes
        return s;
    }();
    const std::string cut = safeText(euros, 100);
    EXPECT_EQ(cut, euros.substr(0, 99) + " [... 2901 bytes cut]");
    EXPECT_TRUE(isValidUtf8(cut));
    EXPECT_EQ(safeText(euros, 3000), euros);
}

TEST(TerminalText, ControlBytesAndEscapeSequencesAreRemoved) {
    EXPECT_EQ(terminalText("red \x1b[31mRED\x1b[0m done"), "red RED done");
    EXPECT_EQ(terminalText("title \x1b]0;pwned\x07 bell \x1b]8;;http://x\x1b\\link\x1b]8;;\x1b\\"), "title  bell link");
    EXPECT_EQ(terminalText("clear\x1b[2J\x1b[H\x1b" "c!"), "clear!");
    EXPECT_EQ(terminalText(std::string("a\rb\bc\x7f" "d\0e", 9)), "abcde");
    EXPECT_EQ(terminalText("keep\ttabs\nand lines"), "keep\ttabs\nand lines");
    EXPECT_EQ(terminalText("c1 \xc2\x9b" "31m csi"), "c1 31m csi");  // U+009B, the one-byte CSI, removed
    EXPECT_EQ(terminalText("caf\xc3\xa9 \xc2\xa0nbsp"), "caf\xc3\xa9 \xc2\xa0nbsp");  // U+00A0 is no control
    EXPECT_EQ(terminalLine("two\nlines\tand a tab"), "two lines and a tab");
    EXPECT_EQ(terminalText(kLatin1), safeText(kLatin1));
    EXPECT_EQ(terminalText("unfinished \x1b["), "unfinished ");
}

TEST(CsvCell, FormulasBecomeTextAndSeparatorsAreQuoted) {
    EXPECT_EQ(csvCell("alice"), "alice");
    EXPECT_EQ(csvCell("=HYPERLINK(\"http://x\",\"y\")"), "\"'=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\"");
    EXPECT_EQ(csvCell("+1"), "\"'+1\"");
    EXPECT_EQ(csvCell("-2+3"), "\"'-2+3\"");
    EXPECT_EQ(csvCell("@SUM(A1)"), "\"'@SUM(A1)\"");
    EXPECT_EQ(csvCell("\t=1"), "\"'\t=1\"");
    EXPECT_EQ(csvCell("\x1b[31m=1+1"), "\"'=1+1\"");  // an escape sequence does not hide the '='
    EXPECT_EQ(csvCell("a,b"), "\"a,b\"");
    EXPECT_EQ(csvCell("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csvCell("two\nlines"), "\"two\nlines\"");
    EXPECT_EQ(csvCell("x=1"), "x=1");  // only the first character matters
    EXPECT_TRUE(isValidUtf8(csvCell(kLatin1)));
}

TEST(SafeFolderName, OrdinaryNamesStayAndOthersCannotCollide) {
    std::set<std::string> taken;
    EXPECT_EQ(safeFolderName("alice", taken), "alice");
    EXPECT_EQ(safeFolderName("bob.smith-2_x", taken), "bob.smith-2_x");
    EXPECT_EQ(safeFolderName("gradebook.csv", taken), "gradebook.csv-2");
    EXPECT_EQ(safeFolderName("INDEX.HTML", taken), "INDEX.HTML-2");
    EXPECT_EQ(safeFolderName("similarity.html", taken), "similarity.html-2");
    EXPECT_EQ(safeFolderName("similarity.json", taken), "similarity.json-2");
    EXPECT_EQ(safeFolderName(".expected", taken), "_expected");
    EXPECT_EQ(safeFolderName("..", taken), "_.");
    EXPECT_EQ(safeFolderName("", taken), "_");
    EXPECT_EQ(safeFolderName("l\xe9" "a", taken), "l_a");
    EXPECT_EQ(safeFolderName("l\xc3\xa9" "a", taken), "l_a-2");  // the same name in UTF-8: a second folder
    EXPECT_EQ(safeFolderName("Alice", taken), "Alice-2");          // not two folders on a case-blind disk
    EXPECT_EQ(safeFolderName("../../etc", taken), "_._.._etc");
    EXPECT_EQ(safeFolderName("\x1b[31m=HYPERLINK(1)", taken), "_31m_HYPERLINK_1_");
    EXPECT_EQ(safeFolderName(std::string(300, 'a'), taken), std::string(100, 'a'));
}

// A report whose every text field holds bytes a student chose.
json hostileReport(const std::string& text) {
    const json item = {{"name", text}, {"status", text}, {"message", text}, {"score", 0.5}, {"max_score", 1.0}};
    const json stage = {{"stage", text},      {"title", text},  {"status", "compile_error"}, {"message", text},
                        {"log", text},        {"score", 1.0},   {"max_score", 10.0},         {"scenes", {item}},
                        {"checks", {item}},   {"hints", {text}}};
    return {{"name", text}, {"submission", text}, {"layout_note", text}, {"status", "error"}, {"message", text},
            {"score", 1.0}, {"max_score", 10.0},  {"stages", {stage, stage}}};
}

TEST(ReportWriters, StudentsBytesGiveValidReportsOfEveryKind) {
    const std::string text = kLatin1 + " <script>alert(1)</script> \x1b[2J\x1b]0;t\x07 =cmd|' /C calc'!A0 \r\n\xff";
    const json report = hostileReport(text);

    const std::string jsonText = reportJsonText(report);  // nlohmann's own dump() throws type_error 316 here
    EXPECT_TRUE(isValidUtf8(jsonText));
    EXPECT_NO_THROW(json::parse(jsonText));
    EXPECT_THROW(report.dump(), json::type_error);

    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_untrusted_" + std::to_string(getpid()));
    fs::create_directories(dir / "class");
    writeHtmlReport(report, dir.string());
    writeClassHtmlReport(json{{"submissions", {report}}}, (dir / "class").string());
    for (const fs::path& page : {dir / "index.html", dir / "class" / "index.html"}) {
        const std::string html = readFile(page.string());
        EXPECT_TRUE(isValidUtf8(html)) << page;
        EXPECT_EQ(html.find("<script>alert"), std::string::npos) << page;
        EXPECT_NE(html.find("&lt;script&gt;alert"), std::string::npos) << page;
    }
    fs::remove_all(dir);

    const std::string csv = gradebookCsv({report});
    EXPECT_TRUE(isValidUtf8(csv));
    EXPECT_EQ(csv.find('\x1b'), std::string::npos);
    EXPECT_NE(csv.find("\"caf\xef\xbf\xbd cr\xef\xbf\xbdme <script>"), std::string::npos) << csv;

    const std::string table = summaryTable(report);
    EXPECT_TRUE(isValidUtf8(table));
    for (char c : table) EXPECT_TRUE(c == '\n' || static_cast<unsigned char>(c) >= 0x20) << int(c);
    EXPECT_TRUE(isValidUtf8(gradescopeResults(report).dump(-1, ' ', false, json::error_handler_t::replace)));
}

TEST(ReportWriters, TheGradebookHasARowPerReportAndTextCellsNeverStartAFormula) {
    const json ok = {{"name", "=HYPERLINK(\"http://evil\",\"click\")"},
                     {"score", 10.0},
                     {"max_score", 10.0},
                     {"stages", {{{"stage", "mip"}, {"status", "passed"}, {"score", 10.0}, {"max_score", 10.0}}}}};
    const json broken = {{"name", "-bob"},
                         {"status", "error"},
                         {"message", "@no stage folder"},
                         {"score", 0.0},
                         {"max_score", 15.0},
                         {"stages",
                          {{{"stage", "minip"}, {"status", "error"}, {"score", 0.0}, {"max_score", 5.0}},
                           {{"stage", "mip"}, {"status", "error"}, {"score", 0.0}, {"max_score", 10.0}}}}};
    EXPECT_EQ(gradebookCsv({ok, broken}),
              "name,score,max_score,mip,minip,problems\n"
              "\"'=HYPERLINK(\"\"http://evil\"\",\"\"click\"\")\",10.00,10.00,10.00,,\n"
              "\"'-bob\",0.00,15.00,0.00,0.00,not graded: @no stage folder\n");
}

}  // namespace
}  // namespace voxlab::testing
