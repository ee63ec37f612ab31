// A source of the layering test's fixture, with its test file.
int Tested() { return 1; }
