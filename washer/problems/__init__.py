"""The washer as continuation problems of the engine. Its modules:

resolve      the family e='washer...' of washer.named_problems: the problem a constants
             file names, with its parameter set
washer       the washer problem e names ('washer', 'washer:frozen', 'washer:forced', ...)
rotating     the rotating-frame problem itself and its Hopf search
oscillator   e='washer:forced': the forced response with an appended oscillator (collocation)
forced       e='washer:shooting': the forced response by shooting, and its studies
torus        the exact whirl: invariant circles of the half-period map
parameters   the PAR map and the reference set they share
auto07p      the same equations as AUTO-07p's C user file (to run AUTO-07p on them)
"""
