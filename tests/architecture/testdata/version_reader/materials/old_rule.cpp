// A plugin that chooses its model by the scene's version instead of a parameter.
bool mitsuba3(const Properties& p) { return p.formatVersion() >= 2; }
