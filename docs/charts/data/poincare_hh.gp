set terminal pngcairo size 800,700 enhanced font 'DejaVu Sans,11'
set output 'poincare_hh.png'
set title 'Henon-Heiles, H = 0.125: section q1 = 0, p1 > 0 (ABA864, h = 0.05)' noenhanced
set xlabel 'q_2'
set ylabel 'p_2'
set key off
set grid lc rgb '#dddddd'
plot 'data/poincare_hh.dat' u 1:2:(column(-2)) w p pt 7 ps 0.25 lc variable
