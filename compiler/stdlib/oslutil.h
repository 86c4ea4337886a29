// oslutil.h: OSL's utility functions (oslutil.h API): wireframe() edge coverage and
// draw_string() text rendering for debugging shaders. Built into Lobe: `#include "oslutil.h"`
// finds this file when no file of that name is on the include path.

#ifndef OSLUTIL_H
#define OSLUTIL_H

// 1 where P lies within line_width of an edge of the current primitive, else 0. edge_type is
// "triangles" (vertices from the "geom:trianglevertices" attribute) or "polygons"/"patches"
// ("geom:numpolyvertices" and "geom:polyvertices"); with raster set the width is in pixels
// (the footprint of P's derivatives across the view direction), otherwise in world units.
// Diffuse rays see no wires: their footprints are too wide to tell.
float wireframe(string edge_type, float line_width, int raster) {
  if (raytype("path:diffuse")) return 0.0;
  point vert[64];
  int count = 0;
  if (edge_type == "triangles") {
    count = 3;
    if (!getattribute("geom:trianglevertices", vert)) return 0.0;
  } else if (edge_type == "polygons" || edge_type == "patches") {
    getattribute("geom:numpolyvertices", count);
    if (count < 3 || !getattribute("geom:polyvertices", vert)) return 0.0;
  }
  float width = 1;
  if (raster) { // mean length of dP/dx and dP/dy projected on the plane across I
    vector dx = Dx(P), dy = Dy(P);
    width = (length(dx - dot(dx, I) * I) + length(dy - dot(dy, I) * I)) / 2;
  }
  // Half the width (the neighbouring face draws the other half), squared to compare with the
  // squared distance to each edge: |edge x (P - vertex)|^2 / |edge|^2.
  width *= 0.5 * line_width;
  width *= width;
  for (int i = 0; i < count; i++) {
    vector edge = vert[i] - vert[i ? i - 1 : count - 1];
    vector c = cross(edge, P - vert[i]);
    if (dot(c, c) < dot(edge, edge) * width) return 1;
  }
  return 0;
}
float wireframe(string edge_type, float line_width) { return wireframe(edge_type, line_width, 1); }
float wireframe(string edge_type) { return wireframe(edge_type, 1.0, 1); }
float wireframe() { return wireframe("polygons", 1.0, 1); }

// 1 where texel (floor(s), floor(t)) of str, drawn in an 8x14 bitmap font, is ink, else 0.
// Characters are 8 texels apart along s, t grows downwards, ASCII '!'..'~' have glyphs. wrap_s
// and wrap_t repeat the text with a gap (the period is the text's width plus 14 texels along s,
// 28 texels along t); a nonzero jitter shifts the repetition by jitter's low bits, as OSL does.
float draw_string(string str, float s, float t, int wrap_s, int wrap_t, int jitter) {
  // The font: Gohu 8x14 (font.gohu.org, WTFPL), characters 33..126, 14 rows each, top row first;
  // a row is two hex digits whose bit k is column k+1 of the glyph (column 0 is blank).
  string font =
      "00080808080808080008080000000024242400000000000000000000" // ! "
      "001414147F14147F14141400000008083E4909093E4848493E080800" // # $
      "000026291610080804344A32000000182424180C522222225C000000" // % &
      "00080808080000000000000000000010080404020202020404081000" // ' (
      "000408101020202020101008040000000008492A1C2A490800000000" // ) *
      "0000000808087F080808000000000000000000000000000C0C080400" // + ,
      "0000000000007E000000000000000000000000000000000C0C000000" // - .
      "404020201010080804040202000000003C4262524A4642423C000000" // / 0
      "000010181412101010101000000000003C424220100804027E000000" // 1 2
      "00003C424040384040423C000000000020302824227E202020000000" // 3 4
      "00007E02023E404040423C00000000003C02023E424242423C000000" // 5 6
      "00007E402020101008080800000000003C4242423C4242423C000000" // 7 8
      "00003C4242427C4040201C0000000000000018180000001818000000" // 9 :
      "000000000C0C0000000C0C0804000000002010080402040810200000" // ; <
      "000000007E0000007E00000000000000000204081020100804020000" // = >
      "003C424040201008000808000000003E41794545456559017E000000" // ? @
      "00003C4242427E4242424200000000003E4242423E4242423E000000" // A B
      "00003C420202020202423C00000000001E224242424242221E000000" // C D
      "00007E0202021E0202027E00000000007E0202021E02020202000000" // E F
      "00003C420202724242423C0000000000424242427E42424242000000" // G H
      "00001C080808080808081C000000000040404040404042423C000000" // I J
      "00004222120A060A122242000000000002020202020202027E000000" // K L
      "000041635549494141414100000000004246464A4A52526262000000" // M N
      "00003C424242424242423C00000000003E4242423E02020202000000" // O P
      "00003C424242425252225C40000000003E4242423E12224242000000" // Q R
      "00003C4202023C4040423C00000000007F0808080808080808000000" // S T
      "000042424242424242423C0000000000424242422424241818000000" // U V
      "00004141494949552222220000000000424224241824244242000000" // W X
      "000041412222140808080800000000007E402010080402027E000000" // Y Z
      "00380808080808080808083800000202040408081010202040400000" // [ backslash
      "001C1010101010101010101C00000008142200000000000000000000" // ] ^
      "00000000000000000000007F00000002040800000000000000000000" // _ `
      "000000003C407C4242625C000000000202023A46424242423E000000" // a b
      "000000003C42020202423C000000004040407C42424242625C000000" // c d
      "000000003C42427E02027C00000000380404043C0404040404000000" // e f
      "000000007C42424242625C40403C000202023A464242424242000000" // g h
      "000808000E080808080838000000001010001810101010101010100E" // i j
      "000202020222120E122242000000000C080808080808080870000000" // k l
      "000000003F494949494949000000000000003E424242424242000000" // m n
      "000000003C42424242423C000000000000003A46424242423E020202" // o p
      "000000007C42424242625C404040000000003A460202020202000000" // q r
      "000000003C02023C40403E000000000808083C080808080830000000" // s t
      "000000004242424242625C0000000000000042424224241818000000" // u v
      "00000000414149495522220000000000000042422418244242000000" // w x
      "000000004242424242625C40403C000000007E20100804027E000000" // y z
      "00700808080808070808080870000008080808080808080808080800" // { |
      "000E101010101060101010100E000000000000464931000000000000"; // } ~
  int hexdigit(int ch) { return ch <= 57 ? ch - 48 : ch - 55; }
  // Ink at column x (0..7) and row y (0..13) of character c.
  int ink(string font, int c, int x, int y) {
    int g = c - 33, col = x - 1;
    if (g < 0 || g > 93 || col < 0 || col > 6 || y < 0 || y > 13) return 0;
    int at = 2 * (14 * g + y);
    int row = 16 * hexdigit(getchar(font, at)) + hexdigit(getchar(font, at + 1));
    return (row >> col) & 1;
  }
  int wrap(int a, int period) { // a modulo period, in [0, period)
    int r = a % period;
    return r < 0 ? r + period : r;
  }
  int width = 8 * strlen(str), height = 14;
  int x = int(floor(s)), y = int(floor(t));
  if (wrap_s) x = wrap(x + (jitter & 15), width + height);
  if (wrap_t) y = wrap(y + ((jitter >> 16) & 15), 2 * height);
  int cell = x / 8;
  return float(ink(font, getchar(str, cell), x - 8 * cell, y));
}

#endif // OSLUTIL_H
