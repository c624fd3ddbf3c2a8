#version 450
// Shadow maps write depth only; the (required) fragment stage has nothing to do.
void main() {}
