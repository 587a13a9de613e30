// A program that links one fixstep component (see CMakeLists.txt) and uses none of it: what it
// needs at run time (ldd) is what the component brings.
int main() {
  return 0;
}
