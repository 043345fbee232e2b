# s t r  ds/dx dt/dx dr/dx  ds/dy dt/dy dr/dy
0.5 0.25 -1.5  0.001 0 0  0 0.001 0
-1e3 2047.99 3.0e-7  1e-3 -2e-3 0.5  0 0 0   # comment
1 2 3 4 5 6 7 8 9
