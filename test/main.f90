program tmain
   print *, 'ok'
end program tmain
