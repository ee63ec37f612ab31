// A source of the layering test's fixture, with no test file.
int Lonely() { return 1; }
