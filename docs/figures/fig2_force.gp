# Fig. 2: radial force against distance (globular figures). Run in this folder.
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 800,500 font 'sans,10'
} else {
  set terminal png size 800,500
}
set output 'fig2_force.png'
set datafile separator ','
set key top right
set grid
set xlabel 'distance D between centres (r_0 = 1, radii 1)'
set ylabel 'radial force (+ repulsion, - attraction)'
set title 'Fig. 2: D S_r (b_1/D^m - b_2/D^n), b_1 = 2, C_r = 1'
set xrange [0.6:2.2]
set yrange [-1:3]
set xzeroaxis lt -1
plot 'fig2_force.csv' using 1:2 with lines lw 2 title 'A: m = 5, n = 3', \
     'fig2_force.csv' using 1:3 with lines lw 2 title 'B: m = 10, n = 3', \
     'fig2_force.csv' using 1:4 with lines lw 2 title 'C: m = 5, n = 1', \
     'fig2_force.csv' using 1:5 with lines lw 2 title 'D: m = 5, n = 4'
