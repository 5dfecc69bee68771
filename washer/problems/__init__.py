"""The washer as continuation problems of the engine: e='washer' (averaged rotating frame),
'washer:frozen', 'washer:forced' (washer.problems.washer)."""
