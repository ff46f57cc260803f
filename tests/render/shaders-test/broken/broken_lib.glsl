// Deliberately broken: undeclared identifier on line 3.
float broken() {
    return undeclaredThing;
}
