function inFuncs
    include_global

    Functs = [];
