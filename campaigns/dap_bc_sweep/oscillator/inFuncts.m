function inFuncts
    include_global

    Functs = [];
