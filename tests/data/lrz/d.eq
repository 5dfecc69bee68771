
   1     1         Eigenvalues  :   Stable:   3
   1     1         Eigenvalue  1: -1.00000E+000  0.00000E+000
   1     1         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     1         Eigenvalue  3: -1.00000E+001  0.00000E+000

   1     2         Eigenvalues  :   Stable:   3
   1     2         Eigenvalue  1: -7.83009E-001  0.00000E+000
   1     2         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     2         Eigenvalue  3: -1.02170E+001  0.00000E+000

   1     3         Eigenvalues  :   Stable:   3
   1     3         Eigenvalue  1: -5.75571E-001  0.00000E+000
   1     3         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     3         Eigenvalue  3: -1.04244E+001  0.00000E+000

   1     4         Eigenvalues  :   Stable:   3
   1     4         Eigenvalue  1: -1.84927E-001  0.00000E+000
   1     4         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     4         Eigenvalue  3: -1.08151E+001  0.00000E+000

   1     5         Eigenvalues  :   Stable:   3
   1     5         Eigenvalue  1:  0.00000E+000  0.00000E+000
   1     5         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     5         Eigenvalue  3: -1.10000E+001  0.00000E+000

   1     6         Eigenvalues  :   Stable:   2
   1     6         Eigenvalue  1:  6.84659E-001  0.00000E+000
   1     6         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     6         Eigenvalue  3: -1.16847E+001  0.00000E+000

   1     7         Eigenvalues  :   Stable:   2
   1     7         Eigenvalue  1:  1.86546E+000  0.00000E+000
   1     7         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     7         Eigenvalue  3: -1.28655E+001  0.00000E+000

   1     8         Eigenvalues  :   Stable:   2
   1     8         Eigenvalue  1:  3.78709E+000  0.00000E+000
   1     8         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     8         Eigenvalue  3: -1.47871E+001  0.00000E+000

   1     9         Eigenvalues  :   Stable:   2
   1     9         Eigenvalue  1:  6.17262E+000  0.00000E+000
   1     9         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1     9         Eigenvalue  3: -1.71726E+001  0.00000E+000

   1    10         Eigenvalues  :   Stable:   2
   1    10         Eigenvalue  1:  8.14734E+000  0.00000E+000
   1    10         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1    10         Eigenvalue  3: -1.91473E+001  0.00000E+000

   1    11         Eigenvalues  :   Stable:   2
   1    11         Eigenvalue  1:  9.87043E+000  0.00000E+000
   1    11         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1    11         Eigenvalue  3: -2.08704E+001  0.00000E+000

   1    12         Eigenvalues  :   Stable:   2
   1    12         Eigenvalue  1:  1.14189E+001  0.00000E+000
   1    12         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1    12         Eigenvalue  3: -2.24189E+001  0.00000E+000

   1    13         Eigenvalues  :   Stable:   2
   1    13         Eigenvalue  1:  1.23955E+001  0.00000E+000
   1    13         Eigenvalue  2: -2.66667E+000  0.00000E+000
   1    13         Eigenvalue  3: -2.33955E+001  0.00000E+000

   2     1         Eigenvalues  :   Stable:   3
   2     1         Eigenvalue  1:  0.00000E+000  0.00000E+000
   2     1         Eigenvalue  2: -2.66667E+000  0.00000E+000
   2     1         Eigenvalue  3: -1.10000E+001  0.00000E+000

   2     2         Eigenvalues  :   Stable:   3
   2     2         Eigenvalue  1: -3.41394E-003  0.00000E+000
   2     2         Eigenvalue  2: -2.66276E+000  0.00000E+000
   2     2         Eigenvalue  3: -1.10005E+001  0.00000E+000

   2     3         Eigenvalues  :   Stable:   3
   2     3         Eigenvalue  1: -1.36712E-002  0.00000E+000
   2     3         Eigenvalue  2: -2.65104E+000  0.00000E+000
   2     3         Eigenvalue  3: -1.10020E+001  0.00000E+000

   2     4         Eigenvalues  :   Stable:   3
   2     4         Eigenvalue  1: -3.29378E-002  0.00000E+000
   2     4         Eigenvalue  2: -2.62906E+000  0.00000E+000
   2     4         Eigenvalue  3: -1.10047E+001  0.00000E+000

   2     5         Eigenvalues  :   Stable:   3
   2     5         Eigenvalue  1: -6.39907E-002  0.00000E+000
   2     5         Eigenvalue  2: -2.59373E+000  0.00000E+000
   2     5         Eigenvalue  3: -1.10089E+001  0.00000E+000

   2     6         Eigenvalues  :   Stable:   3
   2     6         Eigenvalue  1: -1.10546E-001  0.00000E+000
   2     6         Eigenvalue  2: -2.54100E+000  0.00000E+000
   2     6         Eigenvalue  3: -1.10151E+001  0.00000E+000

   2     7         Eigenvalues  :   Stable:   3
   2     7         Eigenvalue  1: -1.77845E-001  0.00000E+000
   2     7         Eigenvalue  2: -2.46527E+000  0.00000E+000
   2     7         Eigenvalue  3: -1.10235E+001  0.00000E+000

   2     8         Eigenvalues  :   Stable:   3
   2     8         Eigenvalue  1: -2.73961E-001  0.00000E+000
   2     8         Eigenvalue  2: -2.35810E+000  0.00000E+000
   2     8         Eigenvalue  3: -1.10346E+001  0.00000E+000

   2     9         Eigenvalues  :   Stable:   3
   2     9         Eigenvalue  1: -4.13326E-001  0.00000E+000
   2     9         Eigenvalue  2: -2.20468E+000  0.00000E+000
   2     9         Eigenvalue  3: -1.10487E+001  0.00000E+000

   2    10         Eigenvalues  :   Stable:   3
   2    10         Eigenvalue  1: -6.30137E-001  0.00000E+000
   2    10         Eigenvalue  2: -1.97049E+000  0.00000E+000
   2    10         Eigenvalue  3: -1.10660E+001  0.00000E+000

   2    11         Eigenvalues  :   Stable:   3
   2    11         Eigenvalue  1: -1.15235E+000  0.00000E+000
   2    11         Eigenvalue  2: -1.42727E+000  0.00000E+000
   2    11         Eigenvalue  3: -1.10870E+001  0.00000E+000

   2    12         Eigenvalues  :   Stable:   3
   2    12         Eigenvalue  1: -1.27736E+000  7.04228E-001
   2    12         Eigenvalue  2: -1.27736E+000 -7.04228E-001
   2    12         Eigenvalue  3: -1.11120E+001  0.00000E+000

   2    13         Eigenvalues  :   Stable:   3
   2    13         Eigenvalue  1: -1.26284E+000  1.05003E+000
   2    13         Eigenvalue  2: -1.26284E+000 -1.05003E+000
   2    13         Eigenvalue  3: -1.11410E+001  0.00000E+000

   2    14         Eigenvalues  :   Stable:   3
   2    14         Eigenvalue  1: -1.24617E+000  1.34463E+000
   2    14         Eigenvalue  2: -1.24617E+000 -1.34463E+000
   2    14         Eigenvalue  3: -1.11743E+001  0.00000E+000

   2    15         Eigenvalues  :   Stable:   3
   2    15         Eigenvalue  1: -1.22727E+000  1.61845E+000
   2    15         Eigenvalue  2: -1.22727E+000 -1.61845E+000
   2    15         Eigenvalue  3: -1.12121E+001  0.00000E+000

   2    16         Eigenvalues  :   Stable:   3
   2    16         Eigenvalue  1: -1.20608E+000  1.88252E+000
   2    16         Eigenvalue  2: -1.20608E+000 -1.88252E+000
   2    16         Eigenvalue  3: -1.12545E+001  0.00000E+000

   2    17         Eigenvalues  :   Stable:   3
   2    17         Eigenvalue  1: -1.18255E+000  2.14219E+000
   2    17         Eigenvalue  2: -1.18255E+000 -2.14219E+000
   2    17         Eigenvalue  3: -1.13016E+001  0.00000E+000

   2    18         Eigenvalues  :   Stable:   3
   2    18         Eigenvalue  1: -1.15664E+000  2.40054E+000
   2    18         Eigenvalue  2: -1.15664E+000 -2.40054E+000
   2    18         Eigenvalue  3: -1.13534E+001  0.00000E+000

   2    19         Eigenvalues  :   Stable:   3
   2    19         Eigenvalue  1: -1.12833E+000  2.65957E+000
   2    19         Eigenvalue  2: -1.12833E+000 -2.65957E+000
   2    19         Eigenvalue  3: -1.14100E+001  0.00000E+000

   2    20         Eigenvalues  :   Stable:   3
   2    20         Eigenvalue  1: -1.09760E+000  2.92065E+000
   2    20         Eigenvalue  2: -1.09760E+000 -2.92065E+000
   2    20         Eigenvalue  3: -1.14715E+001  0.00000E+000

   2    21         Eigenvalues  :   Stable:   3
   2    21         Eigenvalue  1: -1.06443E+000  3.18483E+000
   2    21         Eigenvalue  2: -1.06443E+000 -3.18483E+000
   2    21         Eigenvalue  3: -1.15378E+001  0.00000E+000

   2    22         Eigenvalues  :   Stable:   3
   2    22         Eigenvalue  1: -1.02881E+000  3.45297E+000
   2    22         Eigenvalue  2: -1.02881E+000 -3.45297E+000
   2    22         Eigenvalue  3: -1.16090E+001  0.00000E+000

   2    23         Eigenvalues  :   Stable:   3
   2    23         Eigenvalue  1: -9.90750E-001  3.72578E+000
   2    23         Eigenvalue  2: -9.90750E-001 -3.72578E+000
   2    23         Eigenvalue  3: -1.16852E+001  0.00000E+000

   2    24         Eigenvalues  :   Stable:   3
   2    24         Eigenvalue  1: -9.50253E-001  4.00390E+000
   2    24         Eigenvalue  2: -9.50253E-001 -4.00390E+000
   2    24         Eigenvalue  3: -1.17662E+001  0.00000E+000

   2    25         Eigenvalues  :   Stable:   3
   2    25         Eigenvalue  1: -9.07331E-001  4.28792E+000
   2    25         Eigenvalue  2: -9.07331E-001 -4.28792E+000
   2    25         Eigenvalue  3: -1.18520E+001  0.00000E+000

   2    26         Eigenvalues  :   Stable:   3
   2    26         Eigenvalue  1: -8.62002E-001  4.57840E+000
   2    26         Eigenvalue  2: -8.62002E-001 -4.57840E+000
   2    26         Eigenvalue  3: -1.19427E+001  0.00000E+000

   2    27         Eigenvalues  :   Stable:   3
   2    27         Eigenvalue  1: -8.14290E-001  4.87588E+000
   2    27         Eigenvalue  2: -8.14290E-001 -4.87588E+000
   2    27         Eigenvalue  3: -1.20381E+001  0.00000E+000

   2    28         Eigenvalues  :   Stable:   3
   2    28         Eigenvalue  1: -7.64222E-001  5.18089E+000
   2    28         Eigenvalue  2: -7.64222E-001 -5.18089E+000
   2    28         Eigenvalue  3: -1.21382E+001  0.00000E+000

   2    29         Eigenvalues  :   Stable:   3
   2    29         Eigenvalue  1: -7.11834E-001  5.49399E+000
   2    29         Eigenvalue  2: -7.11834E-001 -5.49399E+000
   2    29         Eigenvalue  3: -1.22430E+001  0.00000E+000

   2    30         Eigenvalues  :   Stable:   3
   2    30         Eigenvalue  1: -6.57166E-001  5.81571E+000
   2    30         Eigenvalue  2: -6.57166E-001 -5.81571E+000
   2    30         Eigenvalue  3: -1.23523E+001  0.00000E+000

   2    31         Eigenvalues  :   Stable:   3
   2    31         Eigenvalue  1: -6.00261E-001  6.14660E+000
   2    31         Eigenvalue  2: -6.00261E-001 -6.14660E+000
   2    31         Eigenvalue  3: -1.24661E+001  0.00000E+000

   2    32         Eigenvalues  :   Stable:   3
   2    32         Eigenvalue  1: -5.41169E-001  6.48726E+000
   2    32         Eigenvalue  2: -5.41169E-001 -6.48726E+000
   2    32         Eigenvalue  3: -1.25843E+001  0.00000E+000

   2    33         Eigenvalues  :   Stable:   3
   2    33         Eigenvalue  1: -4.79946E-001  6.83826E+000
   2    33         Eigenvalue  2: -4.79946E-001 -6.83826E+000
   2    33         Eigenvalue  3: -1.27068E+001  0.00000E+000

   2    34         Eigenvalues  :   Stable:   3
   2    34         Eigenvalue  1: -4.16652E-001  7.20022E+000
   2    34         Eigenvalue  2: -4.16652E-001 -7.20022E+000
   2    34         Eigenvalue  3: -1.28334E+001  0.00000E+000

   2    35         Eigenvalues  :   Stable:   3
   2    35         Eigenvalue  1: -3.51350E-001  7.57378E+000
   2    35         Eigenvalue  2: -3.51350E-001 -7.57378E+000
   2    35         Eigenvalue  3: -1.29640E+001  0.00000E+000

   2    36         Eigenvalues  :   Stable:   3
   2    36         Eigenvalue  1: -2.84113E-001  7.95962E+000
   2    36         Eigenvalue  2: -2.84113E-001 -7.95962E+000
   2    36         Eigenvalue  3: -1.30984E+001  0.00000E+000

   2    37         Eigenvalues  :   Stable:   3
   2    37         Eigenvalue  1: -2.15014E-001  8.35843E+000
   2    37         Eigenvalue  2: -2.15014E-001 -8.35843E+000
   2    37         Eigenvalue  3: -1.32366E+001  0.00000E+000

   2    38         Eigenvalues  :   Stable:   3
   2    38         Eigenvalue  1: -1.44136E-001  8.77095E+000
   2    38         Eigenvalue  2: -1.44136E-001 -8.77095E+000
   2    38         Eigenvalue  3: -1.33784E+001  0.00000E+000

   2    39         Eigenvalues  :   Stable:   3
   2    39         Eigenvalue  1: -7.15638E-002  9.19794E+000
   2    39         Eigenvalue  2: -7.15638E-002 -9.19794E+000
   2    39         Eigenvalue  3: -1.35235E+001  0.00000E+000
   2    40         First Lyapunov coefficient:  2.65509E-004 (subcritical)

   2    40         Eigenvalues  :   Stable:   3
   2    40         Eigenvalue  1: -8.02416E-011  9.62453E+000
   2    40         Eigenvalue  2: -8.02416E-011 -9.62453E+000
   2    40         Eigenvalue  3: -1.36667E+001  0.00000E+000

   2    41         Eigenvalues  :   Stable:   1
   2    41         Eigenvalue  1:  6.92058E-002  1.00432E+001
   2    41         Eigenvalue  2:  6.92058E-002 -1.00432E+001
   2    41         Eigenvalue  3: -1.38051E+001  0.00000E+000

   2    42         Eigenvalues  :   Stable:   1
   2    42         Eigenvalue  1:  1.40144E-001  1.04794E+001
   2    42         Eigenvalue  2:  1.40144E-001 -1.04794E+001
   2    42         Eigenvalue  3: -1.39470E+001  0.00000E+000

   2    43         Eigenvalues  :   Stable:   1
   2    43         Eigenvalue  1:  1.47368E-001  1.05243E+001
   2    43         Eigenvalue  2:  1.47368E-001 -1.05243E+001
   2    43         Eigenvalue  3: -1.39614E+001  0.00000E+000

   2     1         Eigenvalues  :   Stable:   3
   2     1         Eigenvalue  1:  0.00000E+000  0.00000E+000
   2     1         Eigenvalue  2: -2.66667E+000  0.00000E+000
   2     1         Eigenvalue  3: -1.10000E+001  0.00000E+000

   2     2         Eigenvalues  :   Stable:   3
   2     2         Eigenvalue  1: -3.41394E-003  0.00000E+000
   2     2         Eigenvalue  2: -2.66276E+000  0.00000E+000
   2     2         Eigenvalue  3: -1.10005E+001  0.00000E+000

   2     3         Eigenvalues  :   Stable:   3
   2     3         Eigenvalue  1: -1.36712E-002  0.00000E+000
   2     3         Eigenvalue  2: -2.65104E+000  0.00000E+000
   2     3         Eigenvalue  3: -1.10020E+001  0.00000E+000

   2     4         Eigenvalues  :   Stable:   3
   2     4         Eigenvalue  1: -3.29378E-002  0.00000E+000
   2     4         Eigenvalue  2: -2.62906E+000  0.00000E+000
   2     4         Eigenvalue  3: -1.10047E+001  0.00000E+000

   2     5         Eigenvalues  :   Stable:   3
   2     5         Eigenvalue  1: -6.39907E-002  0.00000E+000
   2     5         Eigenvalue  2: -2.59373E+000  0.00000E+000
   2     5         Eigenvalue  3: -1.10089E+001  0.00000E+000

   2     6         Eigenvalues  :   Stable:   3
   2     6         Eigenvalue  1: -1.10546E-001  0.00000E+000
   2     6         Eigenvalue  2: -2.54100E+000  0.00000E+000
   2     6         Eigenvalue  3: -1.10151E+001  0.00000E+000

   2     7         Eigenvalues  :   Stable:   3
   2     7         Eigenvalue  1: -1.77845E-001  0.00000E+000
   2     7         Eigenvalue  2: -2.46527E+000  0.00000E+000
   2     7         Eigenvalue  3: -1.10235E+001  0.00000E+000

   2     8         Eigenvalues  :   Stable:   3
   2     8         Eigenvalue  1: -2.73961E-001  0.00000E+000
   2     8         Eigenvalue  2: -2.35810E+000  0.00000E+000
   2     8         Eigenvalue  3: -1.10346E+001  0.00000E+000

   2     9         Eigenvalues  :   Stable:   3
   2     9         Eigenvalue  1: -4.13326E-001  0.00000E+000
   2     9         Eigenvalue  2: -2.20468E+000  0.00000E+000
   2     9         Eigenvalue  3: -1.10487E+001  0.00000E+000

   2    10         Eigenvalues  :   Stable:   3
   2    10         Eigenvalue  1: -6.30137E-001  0.00000E+000
   2    10         Eigenvalue  2: -1.97049E+000  0.00000E+000
   2    10         Eigenvalue  3: -1.10660E+001  0.00000E+000

   2    11         Eigenvalues  :   Stable:   3
   2    11         Eigenvalue  1: -1.15235E+000  0.00000E+000
   2    11         Eigenvalue  2: -1.42727E+000  0.00000E+000
   2    11         Eigenvalue  3: -1.10870E+001  0.00000E+000

   2    12         Eigenvalues  :   Stable:   3
   2    12         Eigenvalue  1: -1.27736E+000  7.04228E-001
   2    12         Eigenvalue  2: -1.27736E+000 -7.04228E-001
   2    12         Eigenvalue  3: -1.11120E+001  0.00000E+000

   2    13         Eigenvalues  :   Stable:   3
   2    13         Eigenvalue  1: -1.26284E+000  1.05003E+000
   2    13         Eigenvalue  2: -1.26284E+000 -1.05003E+000
   2    13         Eigenvalue  3: -1.11410E+001  0.00000E+000

   2    14         Eigenvalues  :   Stable:   3
   2    14         Eigenvalue  1: -1.24617E+000  1.34463E+000
   2    14         Eigenvalue  2: -1.24617E+000 -1.34463E+000
   2    14         Eigenvalue  3: -1.11743E+001  0.00000E+000

   2    15         Eigenvalues  :   Stable:   3
   2    15         Eigenvalue  1: -1.22727E+000  1.61845E+000
   2    15         Eigenvalue  2: -1.22727E+000 -1.61845E+000
   2    15         Eigenvalue  3: -1.12121E+001  0.00000E+000

   2    16         Eigenvalues  :   Stable:   3
   2    16         Eigenvalue  1: -1.20608E+000  1.88252E+000
   2    16         Eigenvalue  2: -1.20608E+000 -1.88252E+000
   2    16         Eigenvalue  3: -1.12545E+001  0.00000E+000

   2    17         Eigenvalues  :   Stable:   3
   2    17         Eigenvalue  1: -1.18255E+000  2.14219E+000
   2    17         Eigenvalue  2: -1.18255E+000 -2.14219E+000
   2    17         Eigenvalue  3: -1.13016E+001  0.00000E+000

   2    18         Eigenvalues  :   Stable:   3
   2    18         Eigenvalue  1: -1.15664E+000  2.40054E+000
   2    18         Eigenvalue  2: -1.15664E+000 -2.40054E+000
   2    18         Eigenvalue  3: -1.13534E+001  0.00000E+000

   2    19         Eigenvalues  :   Stable:   3
   2    19         Eigenvalue  1: -1.12833E+000  2.65957E+000
   2    19         Eigenvalue  2: -1.12833E+000 -2.65957E+000
   2    19         Eigenvalue  3: -1.14100E+001  0.00000E+000

   2    20         Eigenvalues  :   Stable:   3
   2    20         Eigenvalue  1: -1.09760E+000  2.92065E+000
   2    20         Eigenvalue  2: -1.09760E+000 -2.92065E+000
   2    20         Eigenvalue  3: -1.14715E+001  0.00000E+000

   2    21         Eigenvalues  :   Stable:   3
   2    21         Eigenvalue  1: -1.06443E+000  3.18483E+000
   2    21         Eigenvalue  2: -1.06443E+000 -3.18483E+000
   2    21         Eigenvalue  3: -1.15378E+001  0.00000E+000

   2    22         Eigenvalues  :   Stable:   3
   2    22         Eigenvalue  1: -1.02881E+000  3.45297E+000
   2    22         Eigenvalue  2: -1.02881E+000 -3.45297E+000
   2    22         Eigenvalue  3: -1.16090E+001  0.00000E+000

   2    23         Eigenvalues  :   Stable:   3
   2    23         Eigenvalue  1: -9.90750E-001  3.72578E+000
   2    23         Eigenvalue  2: -9.90750E-001 -3.72578E+000
   2    23         Eigenvalue  3: -1.16852E+001  0.00000E+000

   2    24         Eigenvalues  :   Stable:   3
   2    24         Eigenvalue  1: -9.50253E-001  4.00390E+000
   2    24         Eigenvalue  2: -9.50253E-001 -4.00390E+000
   2    24         Eigenvalue  3: -1.17662E+001  0.00000E+000

   2    25         Eigenvalues  :   Stable:   3
   2    25         Eigenvalue  1: -9.07331E-001  4.28792E+000
   2    25         Eigenvalue  2: -9.07331E-001 -4.28792E+000
   2    25         Eigenvalue  3: -1.18520E+001  0.00000E+000

   2    26         Eigenvalues  :   Stable:   3
   2    26         Eigenvalue  1: -8.62002E-001  4.57840E+000
   2    26         Eigenvalue  2: -8.62002E-001 -4.57840E+000
   2    26         Eigenvalue  3: -1.19427E+001  0.00000E+000

   2    27         Eigenvalues  :   Stable:   3
   2    27         Eigenvalue  1: -8.14290E-001  4.87588E+000
   2    27         Eigenvalue  2: -8.14290E-001 -4.87588E+000
   2    27         Eigenvalue  3: -1.20381E+001  0.00000E+000

   2    28         Eigenvalues  :   Stable:   3
   2    28         Eigenvalue  1: -7.64222E-001  5.18089E+000
   2    28         Eigenvalue  2: -7.64222E-001 -5.18089E+000
   2    28         Eigenvalue  3: -1.21382E+001  0.00000E+000

   2    29         Eigenvalues  :   Stable:   3
   2    29         Eigenvalue  1: -7.11834E-001  5.49399E+000
   2    29         Eigenvalue  2: -7.11834E-001 -5.49399E+000
   2    29         Eigenvalue  3: -1.22430E+001  0.00000E+000

   2    30         Eigenvalues  :   Stable:   3
   2    30         Eigenvalue  1: -6.57166E-001  5.81571E+000
   2    30         Eigenvalue  2: -6.57166E-001 -5.81571E+000
   2    30         Eigenvalue  3: -1.23523E+001  0.00000E+000

   2    31         Eigenvalues  :   Stable:   3
   2    31         Eigenvalue  1: -6.00261E-001  6.14660E+000
   2    31         Eigenvalue  2: -6.00261E-001 -6.14660E+000
   2    31         Eigenvalue  3: -1.24661E+001  0.00000E+000

   2    32         Eigenvalues  :   Stable:   3
   2    32         Eigenvalue  1: -5.41169E-001  6.48726E+000
   2    32         Eigenvalue  2: -5.41169E-001 -6.48726E+000
   2    32         Eigenvalue  3: -1.25843E+001  0.00000E+000

   2    33         Eigenvalues  :   Stable:   3
   2    33         Eigenvalue  1: -4.79946E-001  6.83826E+000
   2    33         Eigenvalue  2: -4.79946E-001 -6.83826E+000
   2    33         Eigenvalue  3: -1.27068E+001  0.00000E+000

   2    34         Eigenvalues  :   Stable:   3
   2    34         Eigenvalue  1: -4.16652E-001  7.20022E+000
   2    34         Eigenvalue  2: -4.16652E-001 -7.20022E+000
   2    34         Eigenvalue  3: -1.28334E+001  0.00000E+000

   2    35         Eigenvalues  :   Stable:   3
   2    35         Eigenvalue  1: -3.51350E-001  7.57378E+000
   2    35         Eigenvalue  2: -3.51350E-001 -7.57378E+000
   2    35         Eigenvalue  3: -1.29640E+001  0.00000E+000

   2    36         Eigenvalues  :   Stable:   3
   2    36         Eigenvalue  1: -2.84113E-001  7.95962E+000
   2    36         Eigenvalue  2: -2.84113E-001 -7.95962E+000
   2    36         Eigenvalue  3: -1.30984E+001  0.00000E+000

   2    37         Eigenvalues  :   Stable:   3
   2    37         Eigenvalue  1: -2.15014E-001  8.35843E+000
   2    37         Eigenvalue  2: -2.15014E-001 -8.35843E+000
   2    37         Eigenvalue  3: -1.32366E+001  0.00000E+000

   2    38         Eigenvalues  :   Stable:   3
   2    38         Eigenvalue  1: -1.44136E-001  8.77095E+000
   2    38         Eigenvalue  2: -1.44136E-001 -8.77095E+000
   2    38         Eigenvalue  3: -1.33784E+001  0.00000E+000

   2    39         Eigenvalues  :   Stable:   3
   2    39         Eigenvalue  1: -7.15638E-002  9.19794E+000
   2    39         Eigenvalue  2: -7.15638E-002 -9.19794E+000
   2    39         Eigenvalue  3: -1.35235E+001  0.00000E+000
   2    40         First Lyapunov coefficient:  2.65509E-004 (subcritical)

   2    40         Eigenvalues  :   Stable:   3
   2    40         Eigenvalue  1: -8.02416E-011  9.62453E+000
   2    40         Eigenvalue  2: -8.02416E-011 -9.62453E+000
   2    40         Eigenvalue  3: -1.36667E+001  0.00000E+000

   2    41         Eigenvalues  :   Stable:   1
   2    41         Eigenvalue  1:  6.92058E-002  1.00432E+001
   2    41         Eigenvalue  2:  6.92058E-002 -1.00432E+001
   2    41         Eigenvalue  3: -1.38051E+001  0.00000E+000

   2    42         Eigenvalues  :   Stable:   1
   2    42         Eigenvalue  1:  1.40144E-001  1.04794E+001
   2    42         Eigenvalue  2:  1.40144E-001 -1.04794E+001
   2    42         Eigenvalue  3: -1.39470E+001  0.00000E+000

   2    43         Eigenvalues  :   Stable:   1
   2    43         Eigenvalue  1:  1.47368E-001  1.05243E+001
   2    43         Eigenvalue  2:  1.47368E-001 -1.05243E+001
   2    43         Eigenvalue  3: -1.39614E+001  0.00000E+000

===============================================

 Total Time    1.673E-01
