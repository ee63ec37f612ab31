// The test file of tested.cpp in the fixture (never built).
