// Tests for the diagnostics table, the SourceManager's location mapping and the rendering.
#include "diag/diagnostics.h"
#include "diag/source_manager.h"

#include <gtest/gtest.h>

using namespace lobe::diag;

TEST(DiagTable, EveryIdHasItsOwnRow) {
  for (int i = 0; i < int(DiagId::kCount); ++i) {
    EXPECT_EQ(int(diag_info(DiagId(i)).id), i);
    EXPECT_NE(std::string(diag_name(DiagId(i))), "");
  }
  EXPECT_STREQ(diag_name(DiagId::err_undeclared), "err_undeclared");
}

TEST(DiagTable, FormatSubstitutesArguments) {
  EXPECT_EQ(format_message("a %0 b %1 %0", {"x", "y"}), "a x b y x");
  EXPECT_EQ(format_message("missing %2.", {"x"}), "missing .");
}

TEST(SourceManager, LineAndColumn) {
  SourceManager sm;
  int id = sm.add_file("a.osl", "ab\ncde\n\nf");
  SourceLoc s = sm.buffer_start(id);
  PresumedLoc p = sm.presumed(s.advanced(4)); // 'd'
  EXPECT_STREQ(p.file, "a.osl");
  EXPECT_EQ(p.line, 2);
  EXPECT_EQ(p.column, 2);
  EXPECT_EQ(sm.presumed(s.advanced(8)).line, 4);
  EXPECT_EQ(sm.line_text(s.advanced(4)), "cde");
  EXPECT_EQ(sm.presumed(s.advanced(9)).column, 2); // end of file is a valid location
  EXPECT_FALSE(sm.presumed(SourceLoc{}).valid());
}

TEST(SourceManager, BuffersDoNotOverlap) {
  SourceManager sm;
  int a = sm.add_file("a", "xyz");
  int b = sm.add_file("b", "");
  int c = sm.add_file("c", "q");
  EXPECT_EQ(sm.buffer_of(sm.buffer_start(a).advanced(3)), a);
  EXPECT_EQ(sm.buffer_of(sm.buffer_start(b)), b);
  EXPECT_EQ(sm.buffer_of(sm.buffer_start(c)), c);
}

TEST(SourceManager, OutputSegmentsMapBackToFiles) {
  SourceManager sm;
  int f = sm.add_file("main.osl", "#define X 1+2\nint a = X;\n");
  SourceLoc fs = sm.buffer_start(f);
  // Output: "\nint a = 1+2;\n": line 1 blank, then "int a = " from the file, "1+2" from
  // the macro invoked at offset 22 (the 'X'), ";\n" from the file again.
  std::vector<SourceManager::Segment> segs;
  segs.push_back({0, fs.advanced(13), true, "", {}});
  segs.push_back({9, fs.advanced(22), false, "X", fs.advanced(8)});
  segs.push_back({12, fs.advanced(23), true, "", {}});
  int o = sm.add_output("\nint a = 1+2;\n", segs);
  SourceLoc os = sm.buffer_start(o);
  PresumedLoc p = sm.presumed(os.advanced(5)); // 'a'
  EXPECT_EQ(p.line, 2);
  EXPECT_EQ(p.column, 5);
  PresumedLoc m = sm.presumed(os.advanced(11)); // '2' in the expansion -> the X
  EXPECT_EQ(m.line, 2);
  EXPECT_EQ(m.column, 9);
  EXPECT_EQ(sm.presumed(os.advanced(12)).column, 10); // ';'
}

TEST(SourceManager, LineDirective) {
  SourceManager sm;
  int f = sm.add_file("a.osl", "x\n#line 100 \"b.osl\"\ny\nz\n");
  sm.add_line_directive(f, 19, 100, "b.osl");
  SourceLoc s = sm.buffer_start(f);
  PresumedLoc y = sm.presumed(s.advanced(19));
  EXPECT_EQ(y.line, 100);
  EXPECT_STREQ(y.file, "b.osl");
  EXPECT_EQ(sm.presumed(s.advanced(21)).line, 101);
  EXPECT_EQ(sm.presumed(s).line, 1);
  EXPECT_STREQ(sm.presumed(s).file, "a.osl");
}

TEST(Render, ErrorWithCaretAndRange) {
  SourceManager sm;
  int f = sm.add_file("t.osl", "float x = foo(1);\n");
  SourceLoc s = sm.buffer_start(f);
  DiagnosticEngine de;
  de.report(DiagId::err_unknown_function, SourceRange(s.advanced(10), s.advanced(13)), {"foo"});
  EXPECT_EQ(render_all(de, sm), "t.osl:1:11: error: use of undeclared function 'foo'\n"
                                "float x = foo(1);\n"
                                "          ^~~\n");
}

TEST(Render, IncludeTrailAndNotes) {
  SourceManager sm;
  int m = sm.add_file("main.osl", "#include \"h.h\"\n");
  int h = sm.add_file("h.h", "\tbad\n", sm.buffer_start(m));
  DiagnosticEngine de;
  de.report(DiagId::err_undeclared, sm.buffer_start(h).advanced(1), {"bad"});
  de.report(DiagId::note_previous_decl, sm.buffer_start(m));
  std::string text = render_all(de, sm);
  EXPECT_EQ(text, "In file included from main.osl:1:\n"
                  "h.h:1:2: error: use of undeclared identifier 'bad'\n"
                  "\tbad\n"
                  "\t^\n"
                  "main.osl:1:1: note: previous definition is here\n"
                  "#include \"h.h\"\n"
                  "^\n");
}

TEST(Engine, CountsAndErrorCap) {
  SourceManager sm;
  int f = sm.add_file("t.osl", "x\n");
  DiagnosticEngine de(3);
  SourceLoc s = sm.buffer_start(f);
  de.report(DiagId::warn_pragma_warning, s, {"w"});
  for (int i = 0; i < 10; ++i) {
    de.report(DiagId::err_undeclared, s, {"x"});
    de.report(DiagId::note_previous_decl, s);
  }
  EXPECT_EQ(de.warning_count(), 1);
  EXPECT_EQ(de.error_count(), 3);
  EXPECT_TRUE(de.stopped());
  // 1 warning + 3 errors with their notes + the fatal "too many errors".
  ASSERT_EQ(de.diagnostics().size(), 8u);
  EXPECT_EQ(de.diagnostics().back().id, DiagId::fatal_too_many_errors);
}

// -Werror: warnings are reported, counted and rendered as errors; notes stay notes.
TEST(Engine, WarningsAsErrors) {
  SourceManager sm;
  int f = sm.add_file("t.osl", "x\n");
  DiagnosticEngine de;
  de.set_warnings_as_errors(true);
  de.report(DiagId::warn_pragma_warning, sm.buffer_start(f), {"careful"});
  de.report(DiagId::note_previous_decl, sm.buffer_start(f));
  EXPECT_EQ(de.warning_count(), 0);
  EXPECT_EQ(de.error_count(), 1);
  ASSERT_EQ(de.diagnostics().size(), 2u);
  EXPECT_EQ(de.diagnostics()[1].severity, Severity::Note);
  EXPECT_EQ(render(de.diagnostics()[0], sm).rfind("t.osl:1:1: error: careful\n", 0), 0u);
}

// resolve_all: what the runtime hands a plugin (one entry per diagnostic, notes included),
// located without the SourceManager.
TEST(Engine, ResolvedReports) {
  SourceManager sm;
  int f = sm.add_file("t.osl", "float a;\n  x = 1;\n");
  DiagnosticEngine de;
  SourceLoc x{sm.buffer_start(f).offset + 11}; // line 2, column 3
  de.report(DiagId::err_undeclared, x, {"x"});
  de.report(DiagId::note_previous_decl, sm.buffer_start(f));
  de.report(DiagId::err_lower_no_shader, SourceRange());
  auto rt = resolve_all(de, sm);
  ASSERT_EQ(rt.size(), 3u);
  EXPECT_EQ(rt[0].severity, Severity::Error);
  EXPECT_EQ(rt[0].id, DiagId::err_undeclared);
  EXPECT_EQ(rt[0].file, "t.osl");
  EXPECT_EQ(rt[0].line, 2);
  EXPECT_EQ(rt[0].column, 3);
  EXPECT_EQ(rt[0].message, "use of undeclared identifier 'x'");
  EXPECT_EQ(rt[0].text, "t.osl:2:3: error: use of undeclared identifier 'x'\n  x = 1;\n  ^\n");
  EXPECT_EQ(rt[1].severity, Severity::Note);
  EXPECT_EQ(rt[1].line, 1);
  EXPECT_EQ(rt[2].file, "");
  EXPECT_EQ(rt[2].line, 0);
  EXPECT_EQ(rt[2].text, "error: no shader declared\n");
}

TEST(Engine, FileReports) {
  Report r = file_report(DiagId::err_ir_invalid, "x.lir", {"op 3 reads nothing"});
  EXPECT_EQ(r.text, "x.lir: error: invalid IR: op 3 reads nothing\n");
  EXPECT_EQ(r.file, "x.lir");
  EXPECT_EQ(r.line, 0);
  EXPECT_EQ(file_report(DiagId::err_shader_not_found, "", {"m"}).text,
            "error: shader 'm' not found\n");
}

// The one caret form: under the column, tildes to the length, tabs kept before the caret so it
// lines up, a place just past the line's end padded out.
TEST(Render, CaretUnder) {
  EXPECT_EQ(caret_under("x = nope;", 4, 4), "x = nope;\n    ^~~~\n");
  EXPECT_EQ(caret_under("\tx = y", 5), "\tx = y\n\t    ^\n");
  EXPECT_EQ(caret_under("f(1", 3), "f(1\n   ^\n");
  EXPECT_EQ(caret_under("f(1", 5), "f(1\n     ^\n");
}
