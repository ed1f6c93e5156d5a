// broken.glsl: a deliberate compile error on line 4, for the include tests.

float broken() {
    return undeclared_variable;
}
