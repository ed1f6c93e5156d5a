#pragma once
// one(): the constant 1, reached through a nested include.
float one() { return 1.0; }
