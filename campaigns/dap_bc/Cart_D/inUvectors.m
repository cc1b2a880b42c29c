function inUvectors
    include_global

    Uvectors = [];
