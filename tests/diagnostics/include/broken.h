// A header with a type error on line 3, column 13.
float broken_helper(float x) {
  float y = "not a number";
  return x;
}
